import { Badge, Button, Center, Group, Loader, Modal, ScrollArea, Stack, Text, UnstyledButton } from "@mantine/core";
import { IconFolder, IconFolderOpen } from "@tabler/icons-react";
import { useEffect, useState } from "react";
import { notifyOk } from "../../lib/notify";
import { ProblemList, UnsavedWarning } from "./ProblemList";
import { type ProjectInfo, type Refusal, listProjects, openProject, refusalOf } from "./projectApi";

const ROW = { padding: "6px 8px", borderRadius: 6, border: "1px solid var(--mantine-color-gray-3)" } as const;

/**
 * The project folders of the projects root. An invalid project is listed with its first problem and can still be
 * tried: opening it shows every problem, and the open project stays open (nothing is written).
 */
export function OpenProjectDialog({ opened, onClose, dirty }: { opened: boolean; onClose: () => void; dirty: boolean }) {
  const [projects, setProjects] = useState<ProjectInfo[] | null>(null);
  const [listError, setListError] = useState<string | null>(null);
  const [busy, setBusy] = useState<string | null>(null);
  const [refusal, setRefusal] = useState<Refusal | null>(null);

  useEffect(() => {
    if (!opened) return;
    setProjects(null);
    setListError(null);
    setRefusal(null);
    listProjects().then(setProjects, (err: unknown) => setListError(refusalOf(err).message));
  }, [opened]);

  const open = async (p: ProjectInfo) => {
    setBusy(p.name);
    setRefusal(null);
    try {
      const title = await openProject(p.name);
      notifyOk("Project opened", `${title} (${p.name})`);
      onClose();
    } catch (err) {
      setRefusal(refusalOf(err));
    } finally {
      setBusy(null);
    }
  };

  return (
    <Modal opened={opened} onClose={onClose} title="Open project" size="lg" centered data-testid="open-project-dialog">
      <Stack gap="sm">
        {dirty && <UnsavedWarning what="Opening another project" />}
        {refusal && <ProblemList refusal={refusal} testId="open-project-error" />}
        {projects === null && !listError && (
          <Center h={80}>
            <Loader size="sm" data-testid="open-project-loading" />
          </Center>
        )}
        {listError && (
          <Text size="sm" c="red">
            Cannot list the projects folder: {listError}
          </Text>
        )}
        {projects?.length === 0 && (
          <Text size="sm" c="dimmed">
            No projects in the projects folder yet — use Save as… or New project….
          </Text>
        )}
        {projects && projects.length > 0 && (
          <ScrollArea.Autosize mah={360} type="auto">
            <Stack gap={4}>
              {projects.map((p) => (
                <UnstyledButton key={p.name} disabled={p.current || busy !== null} style={ROW}
                  onClick={() => void open(p)} data-testid={`open-project-item-${p.name}`}
                  data-valid={p.valid ? "true" : "false"}>
                  <Group gap={10} wrap="nowrap" align="flex-start">
                    {p.current ? (
                      <IconFolderOpen size={18} color="var(--mantine-color-blue-6)" style={{ flex: "none" }} />
                    ) : (
                      <IconFolder size={18} color="var(--mantine-color-gray-6)" style={{ flex: "none" }} />
                    )}
                    <Stack gap={0} style={{ flex: 1, minWidth: 0 }}>
                      <Group gap={6} wrap="nowrap">
                        <Text size="sm" fw={600} truncate="end">
                          {p.title}
                        </Text>
                        {p.current && <Badge size="xs" variant="light">open</Badge>}
                        {!p.valid && <Badge size="xs" color="red" variant="light">invalid</Badge>}
                      </Group>
                      <Text size="xs" c="dimmed" ff="monospace" truncate="end">
                        {p.name}/
                      </Text>
                      {!p.valid && p.error && (
                        <Text size="xs" c="red.7" lineClamp={2} title={p.error}>
                          {p.error}
                        </Text>
                      )}
                    </Stack>
                    {busy === p.name && <Loader size="xs" />}
                  </Group>
                </UnstyledButton>
              ))}
            </Stack>
          </ScrollArea.Autosize>
        )}
        <Group justify="flex-end">
          <Button variant="default" onClick={onClose}>
            Close
          </Button>
        </Group>
      </Stack>
    </Modal>
  );
}
