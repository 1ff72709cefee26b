import { Button, Group, Modal, Stack, Text } from "@mantine/core";
import { useEffect, useState } from "react";
import { notifyOk } from "../../lib/notify";
import { ProblemList } from "./ProblemList";
import { type Refusal, refusalOf, revertProject } from "./projectApi";

/** Reload the project from its folder, discarding the unsaved changes (the controller restarts at cycle 0). */
export function RevertDialog({ opened, onClose, dirty }: { opened: boolean; onClose: () => void; dirty: boolean }) {
  const [busy, setBusy] = useState(false);
  const [refusal, setRefusal] = useState<Refusal | null>(null);
  useEffect(() => {
    if (opened) setRefusal(null);
  }, [opened]);

  const revert = async () => {
    setBusy(true);
    setRefusal(null);
    try {
      const title = await revertProject();
      notifyOk("Project reverted", `${title}: reloaded from its folder`);
      onClose();
    } catch (err) {
      setRefusal(refusalOf(err));
    } finally {
      setBusy(false);
    }
  };

  return (
    <Modal opened={opened} onClose={onClose} title="Revert to the saved project?" size="md" centered>
      <Stack gap="sm">
        <Text size="sm">
          {dirty ? (
            <>The <b>unsaved changes</b> are discarded and</>
          ) : (
            <>There are no unsaved changes; if project.json was edited outside the studio, those edits are loaded:</>
          )}
          {" "}the project is reloaded from its folder into a fresh controller at cycle 0, like opening it again:
          function-block instances are removed and every axis is disabled. Refused while an axis moves.
        </Text>
        {refusal && <ProblemList refusal={refusal} testId="revert-error" />}
        <Group justify="flex-end" gap={8}>
          <Button variant="default" onClick={onClose}>
            Cancel
          </Button>
          <Button color="red" loading={busy} onClick={() => void revert()} data-testid="revert-confirm">
            Revert
          </Button>
        </Group>
      </Stack>
    </Modal>
  );
}
