import { Badge, Button, Checkbox, Group, NumberInput, Select, Text } from "@mantine/core";
import { IconPlayerPlay, IconPlayerStop } from "@tabler/icons-react";
import { useEffect, useRef, useState } from "react";
import uPlot from "uplot";
import { useAxisList, useFb } from "../../hooks/useLive";
import { notifyError } from "../../lib/notify";
import { startCamRun, stopCamRun, useCamRun } from "../../store/camTestRun";
import { axisHistory, onEpoch, onFrame } from "../../store/live";
import { Panel } from "../common/Panel";
import { ControlGuard } from "../control/ControlGuard";

const WINDOW_S = 10;
const HEIGHT = 140;
const axisFont = "11px system-ui, sans-serif";

function chartOptions(width: number): uPlot.Options {
  const axis = (scale: string, stroke: string, side = 3): uPlot.Axis => ({
    scale, side, font: axisFont, size: 52, gap: 3, stroke, grid: side === 1 ? { show: false } : { stroke: "#e9ecef", width: 1 },
    ticks: { stroke: "#ced4da", width: 1, size: 4 },
  });
  return {
    width,
    height: HEIGHT,
    pxAlign: 0,
    cursor: { drag: { x: false, y: false }, points: { size: 5 } },
    legend: { show: true, live: false },
    scales: { x: { time: false }, m: { auto: true }, s: { auto: true } },
    axes: [
      { font: axisFont, size: 24, gap: 2, stroke: "#495057", grid: { stroke: "#e9ecef", width: 1 },
        ticks: { stroke: "#ced4da", width: 1, size: 4 }, values: (_u, splits) => splits.map((s) => `${s.toFixed(1)} s`) },
      axis("m", "#1c7ed6"),
      axis("s", "#e8590c", 1),
    ],
    series: [
      { label: "t" },
      { label: "Master phase", scale: "m", stroke: "#1c7ed6", width: 1.5 },
      { label: "Slave position", scale: "s", stroke: "#e8590c", width: 1.5 },
    ],
  };
}

/** Master phase (position since the cam start, modulo the table's end phase) and slave position over time. */
function CamRunChart({ master, slave, start, period }: { master: string; slave: string; start: number; period: number }) {
  const boxRef = useRef<HTMLDivElement>(null);
  useEffect(() => {
    const box = boxRef.current;
    if (!box) return;
    const plot = new uPlot(chartOptions(Math.max(200, box.clientWidth)), [[], [], []], box);
    let raf = 0;
    const draw = () => {
      raf = 0;
      const m = axisHistory(master);
      const s = axisHistory(slave);
      const n = Math.min(m.t.length, s.t.length);
      const tm = m.t.slice(m.t.length - n);
      const tEnd = n ? tm[n - 1] : 0;
      let i0 = 0;
      while (i0 < n && tm[i0] < tEnd - WINDOW_S) i0++;
      const phase = m.cmdPos.slice(m.t.length - n + i0).map((p) => {
        const x = p - start;
        return period > 0 && x >= 0 ? x % period : x;
      });
      plot.setData([tm.slice(i0), phase, s.cmdPos.slice(s.t.length - n + i0)], false);
      const x0 = Math.max(0, tEnd - WINDOW_S);
      plot.setScale("x", { min: x0, max: Math.max(x0 + WINDOW_S, tEnd) });
    };
    const schedule = () => {
      if (!raf) raf = requestAnimationFrame(draw);
    };
    schedule();
    const offFrame = onFrame(schedule);
    const offEpoch = onEpoch(schedule);
    const ro = new ResizeObserver(() => {
      const w = Math.max(200, box.clientWidth);
      if (Math.abs(w - plot.width) > 1) plot.setSize({ width: w, height: HEIGHT });
    });
    ro.observe(box);
    return () => {
      offFrame();
      offEpoch();
      ro.disconnect();
      if (raf) cancelAnimationFrame(raf);
      plot.destroy();
    };
  }, [master, slave, start, period]);
  return <div ref={boxRef} style={{ width: "100%", minHeight: HEIGHT }} data-testid="cam-run-chart" />;
}

/**
 * Try the saved cam table on the machine: a slave axis cams on a master axis that runs at constant velocity
 * (MC_CamIn + MC_MoveVelocity through the /fb API); the chart shows master phase and slave position live.
 */
export function CamTestRun({ name, phaseEnd, defaultVelocity, dirty }: {
  name: string; phaseEnd: number; defaultVelocity: number; dirty: boolean;
}) {
  const { axes } = useAxisList();
  const run = useCamRun(name);
  const camIn = useFb(run?.camInId ?? null);
  const virtual = axes.find((a) => a.type === "_mcVirServo")?.name ?? axes[0]?.name ?? null;
  const [master, setMaster] = useState<string | null>(null);
  const [slave, setSlave] = useState<string | null>(null);
  const [velocity, setVelocity] = useState<number | string>(defaultVelocity);
  const [periodic, setPeriodic] = useState(true);
  const m = master ?? virtual;
  const s = slave ?? axes.find((a) => a.name !== m)?.name ?? null;
  const options = axes.map((a) => ({ value: a.name, label: a.name }));
  const status = run?.status ?? "idle";
  const busy = status !== "idle";

  const start = async () => {
    if (!m || !s) return;
    const v = Number(velocity);
    try {
      await startCamRun(name, { master: m, slave: s, velocity: v, acceleration: v * 10, periodic });
    } catch (err) {
      notifyError("Cam test run", err);
    }
  };
  const out = camIn?.outputs;
  return (
    <ControlGuard>
    <Panel title="Test run: slave cams on a master at constant velocity" testId="cam-test-run"
      right={
        <Group gap={4}>
          {out && <Badge size="xs" variant="light" color={out.InSync ? "teal" : "gray"} data-testid="cam-run-insync">
            {out.InSync ? "InSync" : out.InCam ? "InCam" : "waiting"}</Badge>}
          {out?.Error === true && <Badge size="xs" color="red" data-testid="cam-run-error">Error {String(out.ErrorID)}</Badge>}
          {out && <Text size="10px" c="dimmed" ff="monospace" data-testid="cam-run-index">Index {String(out.Index)}</Text>}
        </Group>
      }>
      <Group gap={10} align="flex-end" wrap="wrap">
        <Select size="xs" label="Master" data={options} value={m} onChange={setMaster} w={130} disabled={busy}
          allowDeselect={false} data-testid="cam-run-master" />
        <Select size="xs" label="Slave" data={options} value={s} onChange={setSlave} w={130} disabled={busy}
          allowDeselect={false} data-testid="cam-run-slave" />
        <NumberInput size="xs" label="Master velocity" value={velocity} onChange={setVelocity} w={120} disabled={busy}
          data-testid="cam-run-velocity" hideControls allowDecimal thousandSeparator={false}
          rightSection={<Text size="10px" c="dimmed" pr={6}>u/s</Text>} rightSectionPointerEvents="none" />
        <Checkbox size="xs" label="Periodic" checked={periodic} onChange={(e) => setPeriodic(e.currentTarget.checked)}
          disabled={busy} mb={6} />
        {status === "idle" || status === "starting" ? (
          <Button size="xs" leftSection={<IconPlayerPlay size={14} />} onClick={start} loading={status === "starting"}
            disabled={!m || !s || m === s || !(Number(velocity) > 0)} data-testid="cam-run-start">Start</Button>
        ) : (
          <Button size="xs" color="red" leftSection={<IconPlayerStop size={14} />} loading={status === "stopping"}
            onClick={() => void stopCamRun(name, Math.max(1, Number(velocity) * 10))} data-testid="cam-run-stop">
            Stop
          </Button>
        )}
        <Text size="xs" c="dimmed" mb={6}>
          {dirty ? "Runs the saved table: save to try the edits." : "Servo ON for both axes, MC_CamIn, MC_MoveVelocity."}
        </Text>
      </Group>
      {run?.error && <Text size="xs" c="red" mt={4} data-testid="cam-run-message">{run.error}</Text>}
      {m && s && (
        <CamRunChart master={run?.master || m} slave={run?.slave || s} start={run?.startPosition ?? 0}
          period={phaseEnd} />
      )}
    </Panel>
    </ControlGuard>
  );
}
