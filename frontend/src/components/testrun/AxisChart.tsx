import { useEffect, useRef } from "react";
import uPlot from "uplot";
import type { AxisUnits } from "../../lib/format";
import { axisHistory, onEpoch, onFrame } from "../../store/live";
import { Panel } from "../common/Panel";

const WINDOW_S = 10;
const HEIGHT = 170;

function makeOptions(width: number, units: AxisUnits): uPlot.Options {
  const axisFont = "11px system-ui, sans-serif";
  return {
    width,
    height: HEIGHT,
    pxAlign: 0,
    cursor: { drag: { x: false, y: false }, points: { size: 5 } },
    legend: { show: true, live: false },
    scales: {
      x: { time: false },
      pos: { auto: true },
      vel: { auto: true },
    },
    axes: [
      {
        font: axisFont,
        size: 28,
        gap: 2,
        stroke: "#495057",
        grid: { stroke: "#e9ecef", width: 1 },
        ticks: { stroke: "#ced4da", width: 1, size: 4 },
        values: (_u, splits) => splits.map((s) => `${s.toFixed(1)} s`),
      },
      {
        scale: "pos",
        label: `Position [${units.pos}]`,
        labelFont: axisFont,
        labelSize: 14,
        font: axisFont,
        size: 52,
        gap: 3,
        stroke: "#1c7ed6",
        grid: { stroke: "#e9ecef", width: 1 },
        ticks: { stroke: "#ced4da", width: 1, size: 4 },
      },
      {
        scale: "vel",
        side: 1,
        label: `Velocity [${units.vel}]`,
        labelFont: axisFont,
        labelSize: 14,
        font: axisFont,
        size: 52,
        gap: 3,
        stroke: "#e8590c",
        grid: { show: false },
        ticks: { stroke: "#ced4da", width: 1, size: 4 },
      },
    ],
    series: [
      { label: "t", value: (_u, v) => (v === null ? "—" : `${v.toFixed(3)} s`) },
      {
        label: "Cmd pos",
        scale: "pos",
        stroke: "#1c7ed6",
        width: 1.5,
        value: (_u, v) => (v === null ? "—" : v.toFixed(3)),
      },
      {
        label: "Act pos",
        scale: "pos",
        stroke: "#2f9e44",
        width: 1.5,
        dash: [5, 3],
        value: (_u, v) => (v === null ? "—" : v.toFixed(3)),
      },
      {
        label: "Cmd vel",
        scale: "vel",
        stroke: "#e8590c",
        width: 1.2,
        value: (_u, v) => (v === null ? "—" : v.toFixed(2)),
      },
    ],
  };
}

/** Command/actual position and command velocity over the last 10 s of simulated time. */
export function AxisChart({ axis, units }: { axis: string; units: AxisUnits }) {
  const boxRef = useRef<HTMLDivElement>(null);

  useEffect(() => {
    const box = boxRef.current;
    if (!box) return;
    const width = Math.max(200, box.clientWidth);
    const plot = new uPlot(makeOptions(width, units), [[], [], [], []], box);
    let raf = 0;

    const draw = () => {
      raf = 0;
      const h = axisHistory(axis);
      const n = h.t.length;
      const tEnd = n ? h.t[n - 1] : 0;
      let i0 = 0;
      while (i0 < n && h.t[i0] < tEnd - WINDOW_S) i0++;
      plot.setData(
        [h.t.slice(i0), h.cmdPos.slice(i0), h.actPos.slice(i0), h.cmdVel.slice(i0)],
        false,
      );
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
  }, [axis, units]);

  return (
    <Panel title="Trend (last 10 s of simulated time)" testId="axis-chart" bodyPadding={4}>
      <div ref={boxRef} style={{ width: "100%", minHeight: HEIGHT }} data-testid="chart" />
    </Panel>
  );
}
