import { Group, Text, Tooltip } from "@mantine/core";
import { useWsStatus } from "../../hooks/useLive";

/** WebSocket connection state: "live" while snapshots arrive, "offline" otherwise (reconnecting with backoff). */
export function WsIndicator() {
  const status = useWsStatus();
  const live = status === "live";
  const color = live ? "teal" : status === "connecting" ? "yellow" : "red";
  return (
    <Tooltip
      label={live ? "Connected to the controller (live data)" : status === "connecting" ? "Connecting…" : "Connection lost; reconnecting…"}
    >
      <Group gap={5} wrap="nowrap" w={62}>
        <span
          className="led"
          style={{ background: `var(--mantine-color-${color}-6)`, borderColor: `var(--mantine-color-${color}-8)` }}
        />
        <Text size="xs" fw={600} c={live ? "teal.8" : "red.8"} data-testid="ws-status">
          {live ? "live" : "offline"}
        </Text>
      </Group>
    </Tooltip>
  );
}
