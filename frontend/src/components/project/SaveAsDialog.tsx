import { Alert, Button, Checkbox, Group, Modal, Stack, Text, TextInput } from "@mantine/core";
import { useEffect, useState } from "react";
import { notifyOk } from "../../lib/notify";
import { ProblemList } from "./ProblemList";
import { type Refusal, refusalOf, saveProjectAs } from "./projectApi";

/** Save the running project (unsaved changes included) as a new folder; the studio continues in the new folder. */
export function SaveAsDialog({ opened, onClose, current }: { opened: boolean; onClose: () => void; current: string }) {
  const [name, setName] = useState("");
  const [overwrite, setOverwrite] = useState(false);
  const [exists, setExists] = useState(false);
  const [busy, setBusy] = useState(false);
  const [refusal, setRefusal] = useState<Refusal | null>(null);

  useEffect(() => {
    if (!opened) return;
    setName(current ? `${current} copy` : "");
    setOverwrite(false);
    setExists(false);
    setRefusal(null);
  }, [opened, current]);

  const save = async () => {
    setBusy(true);
    setRefusal(null);
    try {
      const path = await saveProjectAs(name.trim(), overwrite);
      notifyOk("Project saved as", path);
      onClose();
    } catch (err) {
      const r = refusalOf(err);
      setExists(r.status === 409 && /exists|open project/.test(r.message));
      setRefusal(r);
    } finally {
      setBusy(false);
    }
  };

  return (
    <Modal opened={opened} onClose={onClose} title="Save project as" size="md" centered>
      <form onSubmit={(e) => { e.preventDefault(); void save(); }}>
        <Stack gap="sm">
          <TextInput label="Project name" description="A new folder in the projects folder (cam data and ESI files are copied)"
            value={name} onChange={(e) => { setName(e.currentTarget.value); setExists(false); setRefusal(null); }}
            error={refusal?.fields.name} data-testid="save-as-name" data-autofocus maxLength={64} />
          {exists ? (
            <Alert color="orange" variant="light" py={6} data-testid="save-as-exists">
              <Text size="sm">{refusal?.message}</Text>
              <Checkbox mt={6} label="Replace it (its project.json is kept as project.json.bak)" checked={overwrite}
                onChange={(e) => setOverwrite(e.currentTarget.checked)} data-testid="save-as-overwrite" />
            </Alert>
          ) : (
            refusal && <ProblemList refusal={refusal} testId="save-as-error" />
          )}
          <Group justify="flex-end" gap={8}>
            <Button variant="default" onClick={onClose}>
              Cancel
            </Button>
            <Button type="submit" loading={busy} disabled={!name.trim() || (exists && !overwrite)}
              data-testid="save-as-confirm">
              Save
            </Button>
          </Group>
        </Stack>
      </form>
    </Modal>
  );
}
