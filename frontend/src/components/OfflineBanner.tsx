import { Group, Loader, Text } from "@mantine/core";
import { IconPlugConnectedX } from "@tabler/icons-react";
import { useLive } from "../hooks/useLive";

/** Shown while the WebSocket is down: the values on screen are then the last ones received. */
export function OfflineBanner() {
  const ws = useLive((s) => s.ws);
  const hadData = useLive((s) => s.controller !== null);
  if (ws === "live") return null;
  return (
    <Group
      gap={8}
      px="sm"
      py={4}
      wrap="nowrap"
      data-testid="offline-banner"
      style={{ background: "var(--mantine-color-red-0)", borderBottom: "1px solid var(--mantine-color-red-3)", flex: "none" }}
    >
      <IconPlugConnectedX size={16} color="var(--mantine-color-red-7)" />
      <Text size="xs" c="red.8" fw={600}>
        {ws === "connecting" && !hadData ? "Connecting to the controller…" : "No connection to the controller."}
      </Text>
      <Text size="xs" c="red.8">
        {hadData ? "The values shown are the last ones received. " : ""}Reconnecting automatically
      </Text>
      <Loader size={12} color="red" />
    </Group>
  );
}
