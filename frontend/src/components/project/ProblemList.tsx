import { Alert, Badge, Group, ScrollArea, Stack, Text } from "@mantine/core";
import { IconAlertTriangle } from "@tabler/icons-react";
import type { Refusal } from "./projectApi";

const TITLES: Record<number, string> = {
  404: "Not found",
  409: "Not possible now",
  422: "The project cannot be opened",
};

/** A refused project operation: the summary and every problem in the files with its JSON path. */
export function ProblemList({ refusal, title, testId }: { refusal: Refusal; title?: string; testId: string }) {
  const fieldOnly = !refusal.message && refusal.problems.length === 0;
  if (fieldOnly) return null;
  return (
    <Alert color={refusal.status === 409 ? "orange" : "red"} variant="light" icon={<IconAlertTriangle size={16} />}
      title={title ?? (refusal.status ? (TITLES[refusal.status] ?? `Refused (${refusal.status})`) : "Refused")}
      data-testid={testId}>
      <Stack gap={4}>
        {refusal.message && (
          <Text size="sm" style={{ whiteSpace: "pre-wrap", wordBreak: "break-word" }} data-testid={`${testId}-message`}>
            {refusal.message}
          </Text>
        )}
        {refusal.problems.length > 0 && (
          <ScrollArea.Autosize mah={180} type="auto">
            <Stack gap={2}>
              {refusal.problems.map((p, k) => (
                <Group key={k} gap={6} wrap="nowrap" align="baseline" data-testid={`${testId}-problem`}>
                  {p.code && (
                    <Badge size="sm" color="red" variant="filled" radius="xs" style={{ flex: "none" }}>
                      {p.code}
                    </Badge>
                  )}
                  <Text size="xs">
                    {p.path && (
                      <Text span ff="monospace" size="xs" fw={600}>
                        {p.path}
                      </Text>
                    )}
                    {p.path ? ": " : ""}
                    {p.msg}
                  </Text>
                </Group>
              ))}
            </Stack>
          </ScrollArea.Autosize>
        )}
        {refusal.status === 422 && (
          <Text size="xs" c="dimmed">
            Nothing was changed: the open project stays open and the files on disk are left as they are.
          </Text>
        )}
      </Stack>
    </Alert>
  );
}

/** Shown in the dialogs that replace the running project while it has unsaved changes. */
export function UnsavedWarning({ what }: { what: string }) {
  return (
    <Alert color="orange" variant="light" icon={<IconAlertTriangle size={16} />} py={6}
      data-testid="project-unsaved-warning">
      <Text size="sm">
        The open project has <b>unsaved changes</b>. {what} discards them — save first to keep them.
      </Text>
    </Alert>
  );
}
