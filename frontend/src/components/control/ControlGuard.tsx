import { Button, Group, Text } from "@mantine/core";
import { IconLock } from "@tabler/icons-react";
import type { ReactNode } from "react";
import { useControlHolder, useReadOnly } from "../../hooks/useControl";
import { takeControl } from "../../store/control";

function since(holderSince: number): string {
  return new Date(holderSince * 1000).toLocaleTimeString([], { hour: "2-digit", minute: "2-digit" });
}

/** "Read-only: X holds test-run control" with a button to take it (forcing; X's jogs stop). */
export function ReadOnlyHint() {
  const holder = useControlHolder();
  const readOnly = useReadOnly();
  if (!readOnly || !holder) return null;
  return (
    <Group
      gap={8}
      px="sm"
      py={6}
      wrap="nowrap"
      data-testid="readonly-hint"
      style={{
        background: "var(--mantine-color-orange-0)",
        border: "1px solid var(--mantine-color-orange-3)",
        borderRadius: "var(--mantine-radius-sm)",
      }}
    >
      <IconLock size={16} color="var(--mantine-color-orange-7)" style={{ flex: "none" }} />
      <Text size="xs" c="orange.9" style={{ flex: 1, minWidth: 0 }}>
        Read-only: test-run control is held by <b>{holder.name}</b> since {since(holder.since_s)}. You can watch;
        to operate, take control (their jogs stop).
      </Text>
      <Button size="compact-xs" color="orange" variant="light" onClick={() => void takeControl(true)}
        data-testid="readonly-take">
        Take control
      </Button>
    </Group>
  );
}

/**
 * Test-run controls inside are disabled (a disabled fieldset, which reaches every button and input) while another
 * client holds test-run control; with `hint`, the read-only notice is shown above them.
 */
export function ControlGuard({ children, hint = true }: { children: ReactNode; hint?: boolean }) {
  const readOnly = useReadOnly();
  return (
    <>
      {hint && <ReadOnlyHint />}
      <fieldset className="control-guard" disabled={readOnly} data-readonly={readOnly ? "true" : "false"}>
        {children}
      </fieldset>
    </>
  );
}
