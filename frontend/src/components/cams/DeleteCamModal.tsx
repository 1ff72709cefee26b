import { Button, Group, Modal, Text } from "@mantine/core";
import { useState } from "react";
import { notifyError, notifyOk } from "../../lib/notify";
import { deleteCam } from "../../store/cams";

/** Asks before a cam table is deleted from the project (its CSV file goes too). */
export function DeleteCamModal({ name, onClose }: { name: string | null; onClose: () => void }) {
  const [busy, setBusy] = useState(false);
  return (
    <Modal opened={name !== null} onClose={onClose} title="Delete cam table?" size="sm" centered>
      <Text size="sm">
        Delete <b>{name}</b> from the project? Its data file <code>cams/{name}.csv</code> is removed and the
        controller no longer has the cam data variable.
      </Text>
      <Group justify="flex-end" mt="md" gap={8}>
        <Button variant="default" onClick={onClose}>Keep</Button>
        <Button color="red" loading={busy} data-testid="cam-delete-confirm"
          onClick={async () => {
            if (name === null) return;
            setBusy(true);
            try {
              await deleteCam(name);
              notifyOk(`Cam table ${name} deleted`);
              onClose();
            } catch (err) {
              notifyError(`Delete ${name}`, err);
            } finally {
              setBusy(false);
            }
          }}>
          Delete
        </Button>
      </Group>
    </Modal>
  );
}
