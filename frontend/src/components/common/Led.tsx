import { Group, Text } from "@mantine/core";

interface LedProps {
  label: string;
  on: boolean;
  /** Mantine colour of the lit LED */
  color?: string;
  testId?: string;
  title?: string;
}

/** A named boolean as a small status LED. `data-active` carries the value for scripts. */
export function Led({ label, on, color = "teal", testId, title }: LedProps) {
  return (
    <Group gap={5} wrap="nowrap" data-testid={testId} data-active={on ? "true" : "false"} title={title ?? label}>
      <span
        className="led"
        style={on ? { background: `var(--mantine-color-${color}-6)`, borderColor: `var(--mantine-color-${color}-8)` } : undefined}
      />
      <Text size="xs" c={on ? "dark" : "dimmed"} fw={on ? 600 : 400} style={{ whiteSpace: "nowrap" }}>
        {label}
      </Text>
    </Group>
  );
}
