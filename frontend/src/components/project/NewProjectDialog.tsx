import { Button, Group, Loader, Modal, Radio, Stack, Text, TextInput } from "@mantine/core";
import { useEffect, useState } from "react";
import { notifyOk } from "../../lib/notify";
import { ProblemList, UnsavedWarning } from "./ProblemList";
import { type ProjectTemplate, type Refusal, listTemplates, newProject, refusalOf } from "./projectApi";

/** New project from a template (GET /project-templates): a new folder in the projects root, opened at once. */
export function NewProjectDialog({ opened, onClose, dirty }: { opened: boolean; onClose: () => void; dirty: boolean }) {
  const [templates, setTemplates] = useState<ProjectTemplate[] | null>(null);
  const [template, setTemplate] = useState("single-axis");
  const [name, setName] = useState("");
  const [busy, setBusy] = useState(false);
  const [refusal, setRefusal] = useState<Refusal | null>(null);

  useEffect(() => {
    if (!opened) return;
    setRefusal(null);
    setTemplates(null);
    listTemplates().then(setTemplates, (err: unknown) => setRefusal(refusalOf(err)));
  }, [opened]);

  const create = async () => {
    setBusy(true);
    setRefusal(null);
    try {
      const title = await newProject(name.trim(), template);
      notifyOk("New project", `${title}, from the ${template} template`);
      setName("");
      onClose();
    } catch (err) {
      setRefusal(refusalOf(err));
    } finally {
      setBusy(false);
    }
  };

  return (
    <Modal opened={opened} onClose={onClose} title="New project from a template" size="lg" centered>
      <form onSubmit={(e) => { e.preventDefault(); void create(); }}>
        <Stack gap="sm">
          {dirty && <UnsavedWarning what="Creating a new project" />}
          <TextInput label="Project name" description="The folder in the projects folder; also the project's name"
            placeholder="Line 3" value={name} onChange={(e) => setName(e.currentTarget.value)} data-autofocus
            error={refusal?.fields.name} data-testid="new-project-name" maxLength={64} />
          {templates === null ? (
            <Loader size="sm" />
          ) : (
            <Radio.Group label="Template" value={template} onChange={setTemplate} error={refusal?.fields.template}>
              <Stack gap={6} mt={4}>
                {templates.map((t) => (
                  <Radio.Card key={t.name} value={t.name} p="xs" radius="sm" data-testid={`new-project-template-${t.name}`}>
                    <Group wrap="nowrap" align="flex-start" gap={8}>
                      <Radio.Indicator />
                      <Stack gap={0}>
                        <Text size="sm" fw={600}>
                          {t.name}{" "}
                          <Text span size="xs" c="dimmed" fw={400}>
                            {t.axes} axes{t.groups ? `, ${t.groups} groups` : ""}{t.cams ? `, ${t.cams} cam tables` : ""}
                          </Text>
                        </Text>
                        <Text size="xs" c="dimmed" lineClamp={2}>
                          {t.description}
                        </Text>
                      </Stack>
                    </Group>
                  </Radio.Card>
                ))}
              </Stack>
            </Radio.Group>
          )}
          {refusal && <ProblemList refusal={refusal} testId="new-project-error" />}
          <Group justify="flex-end" gap={8}>
            <Button variant="default" onClick={onClose}>
              Cancel
            </Button>
            <Button type="submit" loading={busy} disabled={!name.trim() || templates === null}
              data-testid="new-project-create">
              Create and open
            </Button>
          </Group>
        </Stack>
      </form>
    </Modal>
  );
}
