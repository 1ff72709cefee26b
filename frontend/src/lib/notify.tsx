import { Stack, Text } from "@mantine/core";
import { notifications } from "@mantine/notifications";
import { ApiError } from "../api/client";

const REJECTED: Record<number, string> = {
  400: "Bad request",
  404: "Not found",
  401: "Access token needed",
  409: "Not possible now",
  422: "Invalid input",
  423: "Read-only: another client has test-run control",
};

/** Show a failed API call as a notification: the message and, for field errors, the field (`loc`). */
export function notifyError(action: string, err: unknown): void {
  if (err instanceof ApiError) {
    const issues = err.issues;
    notifications.show({
      color: "red",
      title: `${action}: ${REJECTED[err.status] ?? "Error"} (${err.status})`,
      autoClose: 8000,
      message: issues.length ? (
        <Stack gap={2}>
          {issues.map((i, k) => (
            <Text size="sm" key={k}>
              {i.field && (
                <Text span ff="monospace" size="sm" fw={600}>
                  {i.field}
                </Text>
              )}
              {i.field ? ": " : ""}
              {i.msg}
            </Text>
          ))}
        </Stack>
      ) : (
        err.message
      ),
    });
    return;
  }
  notifications.show({
    color: "red",
    title: `${action} failed`,
    message: err instanceof Error ? err.message : String(err),
    autoClose: 8000,
  });
}

export function notifyOk(title: string, message?: string): void {
  notifications.show({ color: "teal", title, message: message ?? "", autoClose: 3000 });
}
