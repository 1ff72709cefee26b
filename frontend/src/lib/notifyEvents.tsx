/**
 * Faults from the controller's event log as notifications, wherever the user is working (issue 8).
 *
 * Every new event of level minor fault or above pops one notification with the code, the source, the manual's
 * event name and a "Show in event log" action — at most BURST of them per WINDOW_MS. Further faults inside the
 * window (a fault storm: a disconnected slave error-stops its axis and every instance on it) are counted in one
 * summary notification, updated in place, so the screen is never flooded (decision D126).
 */
import { Button, Group, Stack, Text } from "@mantine/core";
import { notifications } from "@mantine/notifications";
import type { EventOut } from "../api/types";
import { focusEvent } from "../store/events";

export const BURST = 3;
export const WINDOW_MS = 5000;
const SUMMARY_ID = "event-fault-summary";

let shown: number[] = []; // times of the notifications shown in the current window
let suppressed = 0;
let lastSuppressed: EventOut | null = null;
let summaryOpen = false;

function levelTitle(level: string): string {
  return `${level[0].toUpperCase()}${level.slice(1)}`;
}

function ShowButton({ seq, id }: { seq: number; id: string }) {
  return (
    <Button
      size="compact-xs"
      variant="light"
      data-testid="notification-show-event"
      onClick={() => {
        focusEvent(seq);
        notifications.hide(id);
      }}
    >
      Show in event log
    </Button>
  );
}

function showOne(e: EventOut): void {
  const id = `event-${e.seq}`;
  notifications.show({
    id,
    color: e.level === "minor fault" ? "orange" : "red",
    title: `${levelTitle(e.level)} · ${e.code} · ${e.source_name || e.source}`,
    autoClose: 8000,
    withBorder: true,
    message: (
      <Stack gap={4} data-testid="fault-notification" data-seq={e.seq}>
        <Text size="sm" fw={600}>
          {e.message}
        </Text>
        {e.correction && (
          <Text size="xs" lineClamp={3}>
            {e.correction}
          </Text>
        )}
        <Group gap={6}>
          <ShowButton seq={e.seq} id={id} />
          {e.instruction && (
            <Text size="xs" c="dimmed">
              {e.instruction}
            </Text>
          )}
        </Group>
      </Stack>
    ),
  });
}

function showSummary(): void {
  const e = lastSuppressed;
  if (!e) return;
  const body = {
    id: SUMMARY_ID,
    onClose: () => {
      summaryOpen = false;
    },
    color: "red",
    title: `${suppressed} more fault${suppressed === 1 ? "" : "s"}`,
    autoClose: 10000,
    withBorder: true,
    message: (
      <Stack gap={4} data-testid="fault-summary-notification">
        <Text size="xs">
          Latest: {e.code} · {e.source_name || e.source} · {e.message}
        </Text>
        <Group gap={6}>
          <ShowButton seq={e.seq} id={SUMMARY_ID} />
        </Group>
      </Stack>
    ),
  };
  // updated in place while it is on screen
  if (summaryOpen) {
    notifications.update(body);
  } else {
    summaryOpen = true;
    notifications.show(body);
  }
}

/** Pop notifications for the new faults among `fresh` (oldest first), rate-limited. */
export function notifyFaults(fresh: EventOut[], now: number = Date.now()): void {
  shown = shown.filter((t) => now - t < WINDOW_MS);
  if (!shown.length) {
    suppressed = 0;
  }
  for (const e of fresh) {
    if (shown.length < BURST) {
      shown.push(now);
      showOne(e);
    } else {
      suppressed += 1;
      lastSuppressed = e;
    }
  }
  if (lastSuppressed && suppressed > 0 && fresh.includes(lastSuppressed)) showSummary();
}
