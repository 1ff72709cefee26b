import { Group, Stack, Text, Tooltip } from "@mantine/core";
import { useMediaQuery } from "@mantine/hooks";
import type { ReactNode } from "react";
import { useLive } from "../../hooks/useLive";
import { fixed } from "../../lib/format";

function Readout({ label, children, testId, w }: { label: string; children: ReactNode; testId: string; w: number }) {
  return (
    <Stack gap={0} w={w} align="flex-end">
      <Text size="10px" c="dimmed" tt="uppercase" lh={1.2} style={{ letterSpacing: "0.04em" }}>
        {label}
      </Text>
      <Text size="sm" className="num" lh={1.25} data-testid={testId}>
        {children}
      </Text>
    </Stack>
  );
}

/** Live controller read-outs; each subscribes to one number so the rest of the header does not re-render. */
export function Readouts() {
  const cycle = useLive((s) => s.controller?.cycle ?? null);
  const time = useLive((s) => s.controller?.time_s ?? null);
  const rtf = useLive((s) => s.controller?.rtf ?? null);
  const overruns = useLive((s) => s.controller?.overruns ?? null);
  const taskUs = useLive((s) => s.controller?.cycle_time_us ?? null);
  const taskMaxUs = useLive((s) => s.controller?.cycle_time_max_us ?? null);
  const periodUs = useLive((s) => (s.controller ? s.controller.period_s * 1e6 : null));
  const live = useLive((s) => s.ws === "live");
  // at 1366 px the header also holds the project and control buttons: tighter, overruns in the RTF tooltip
  const wide = useMediaQuery("(min-width: 1600px)", true);
  return (
    <Group gap={wide ? "md" : 10} wrap="nowrap" style={{ opacity: live ? 1 : 0.45 }}
      title={live ? undefined : "Stale: not connected"}>
      <Readout label="Cycle" testId="cycle" w={wide ? 78 : 66}>
        {cycle ?? "—"}
      </Readout>
      <Readout label="Sim. time [s]" testId="sim-time" w={wide ? 84 : 78}>
        {fixed(time, 3)}
      </Readout>
      <Tooltip label={`Real-time factor (simulated ÷ wall-clock time); overruns: ${overruns ?? "—"} periods that finished after their deadline`}
        openDelay={300} multiline w={260}>
        <div>
          <Readout label="RTF" testId="rtf" w={36}>
            {fixed(rtf, 2)}
          </Readout>
        </div>
      </Tooltip>
      {wide && (
        <Readout label="Overruns" testId="overruns" w={58}>
          {overruns ?? "—"}
        </Readout>
      )}
      <Tooltip
        label={
          taskUs && periodUs
            ? `Task monitor: a control period takes ${fixed(taskUs, 0)} µs on average, at most ${fixed(taskMaxUs, 0)} µs ` +
              `(last half second) — ${fixed((100 * taskUs) / periodUs, 0)} % of the ${fixed(periodUs, 0)} µs period`
            : "Task monitor: computation time of a control period (0 while paused)"
        }
        openDelay={300}
      >
        <div>
          <Readout label="Task" testId="task-time" w={wide ? 64 : 58}>
            {taskUs ? fixed(taskUs, 0) : "—"} <span className="unit">µs</span>
          </Readout>
        </div>
      </Tooltip>
    </Group>
  );
}
