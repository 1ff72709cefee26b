import { ActionIcon, Anchor, Kbd, Popover, Stack, Table, Text } from "@mantine/core";
import { IconHelp } from "@tabler/icons-react";
import { SHORTCUTS } from "../../hooks/useShortcuts";

export function HelpPopover() {
  return (
    <Popover position="bottom-end" width={360} shadow="md" withArrow>
      <Popover.Target>
        <ActionIcon aria-label="Help and keyboard shortcuts" data-testid="help-button">
          <IconHelp size={18} />
        </ActionIcon>
      </Popover.Target>
      <Popover.Dropdown>
        <Stack gap="xs">
          <Text size="sm" fw={600}>
            Keyboard shortcuts
          </Text>
          <Table withRowBorders={false} verticalSpacing={2}>
            <Table.Tbody>
              {SHORTCUTS.map((s) => (
                <Table.Tr key={s.keys}>
                  <Table.Td style={{ whiteSpace: "nowrap", verticalAlign: "top" }}>
                    <Kbd size="xs">{s.keys}</Kbd>
                  </Table.Td>
                  <Table.Td>{s.action}</Table.Td>
                </Table.Tr>
              ))}
            </Table.Tbody>
          </Table>
          <Text size="xs" c="dimmed">
            Jog buttons are dead-man switches: the axis moves only while the button is held and this page keeps
            renewing the lease; it decelerates 0.5 s after the page or the network goes away.
          </Text>
          <Anchor href="/docs" target="_blank" size="xs">
            REST API reference (/docs)
          </Anchor>
        </Stack>
      </Popover.Dropdown>
    </Popover>
  );
}
