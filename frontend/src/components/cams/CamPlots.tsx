import { useEffect, useRef } from "react";
import uPlot from "uplot";

export interface CamSeries {
  phase: number[];
  distance: number[];
  velocity: number[] | null;
  acceleration: number[] | null;
  jerk: number[] | null;
}

interface PlotDef {
  key: keyof Omit<CamSeries, "phase">;
  label: string;
  unit: string;
  color: string;
}

const PLOTS: PlotDef[] = [
  { key: "distance", label: "Displacement", unit: "", color: "#1c7ed6" },
  { key: "velocity", label: "Velocity", unit: "/s", color: "#e8590c" },
  { key: "acceleration", label: "Acceleration", unit: "/s²", color: "#2f9e44" },
  { key: "jerk", label: "Jerk", unit: "/s³", color: "#ae3ec9" },
];

const HEIGHT = 105;
const SYNC_KEY = "cam-editor";
const axisFont = "11px system-ui, sans-serif";

function fmt(v: number | null | undefined): string {
  if (v === null || v === undefined || !Number.isFinite(v)) return "—";
  const a = Math.abs(v);
  if (a !== 0 && (a >= 1e6 || a < 1e-3)) return v.toExponential(3);
  return v.toFixed(a >= 100 ? 1 : 3);
}

function tickFmt(_u: uPlot, splits: number[]): string[] {
  return splits.map((s) => {
    const a = Math.abs(s);
    return a >= 1e5 ? s.toExponential(1) : String(+s.toPrecision(4));
  });
}

function options(def: PlotDef, width: number, units: string, onZoom: (min: number, max: number) => void): uPlot.Options {
  return {
    width,
    height: HEIGHT,
    pxAlign: 0,
    cursor: {
      sync: { key: SYNC_KEY, setSeries: false },
      drag: { x: true, y: false, setScale: true },
      points: { size: 5 },
    },
    legend: { show: true, live: true },
    scales: { x: { time: false } },
    axes: [
      { font: axisFont, size: 24, gap: 2, stroke: "#495057", grid: { stroke: "#e9ecef", width: 1 },
        ticks: { stroke: "#ced4da", width: 1, size: 4 }, values: tickFmt },
      { font: axisFont, size: 58, gap: 3, stroke: def.color, grid: { stroke: "#e9ecef", width: 1 },
        ticks: { stroke: "#ced4da", width: 1, size: 4 }, values: tickFmt },
    ],
    series: [
      { label: "Phase", value: (_u, v) => fmt(v) },
      { label: `${def.label} [${units}${def.unit}]`, stroke: def.color, width: 1.5, value: (_u, v) => fmt(v) },
    ],
    hooks: {
      setScale: [
        (u, key) => {
          if (key !== "x") return;
          const { min, max } = u.scales.x;
          if (min !== undefined && max !== undefined && min !== null && max !== null) onZoom(min, max);
        },
      ],
    },
  };
}

/**
 * Displacement, velocity, acceleration and jerk of the cam over the master phase: four uPlot charts with one cursor
 * (uPlot's cursor sync) and one zoom (drag to zoom any chart, the others follow; double-click resets).
 */
export function CamPlots({ data, units, testId }: { data: CamSeries | null; units: string; testId?: string }) {
  const boxes = useRef<(HTMLDivElement | null)[]>([]);
  const plots = useRef<uPlot[]>([]);
  const zooming = useRef(false);

  useEffect(() => {
    const created: uPlot[] = [];
    const zoomAll = (min: number, max: number) => {
      if (zooming.current) return;
      zooming.current = true;
      for (const p of created) {
        const x = p.scales.x;
        if (x.min !== min || x.max !== max) p.setScale("x", { min, max });
      }
      zooming.current = false;
    };
    PLOTS.forEach((def, i) => {
      const box = boxes.current[i];
      if (!box) return;
      const width = Math.max(200, box.clientWidth);
      created.push(new uPlot(options(def, width, units, zoomAll), [[], []], box));
    });
    plots.current = created;
    const ro = new ResizeObserver(() => {
      created.forEach((p, i) => {
        const box = boxes.current[i];
        if (!box) return;
        const w = Math.max(200, box.clientWidth);
        if (Math.abs(w - p.width) > 1) p.setSize({ width: w, height: HEIGHT });
      });
    });
    boxes.current.forEach((b) => b && ro.observe(b));
    return () => {
      ro.disconnect();
      created.forEach((p) => p.destroy());
      plots.current = [];
    };
  }, [units]);

  useEffect(() => {
    plots.current.forEach((p, i) => {
      const ys = data ? data[PLOTS[i].key] : null;
      p.setData([data?.phase ?? [], ys ?? []] as uPlot.AlignedData, true);
    });
  }, [data, units]);

  return (
    <div className="cam-plots" data-testid={testId}>
      {PLOTS.map((def, i) => (
        <div key={def.key} className="cam-plot" data-testid={`cam-plot-${def.key}`}
          data-points={data?.phase.length ?? 0}
          data-empty={!data || !data[def.key] ? "true" : "false"}>
          <div ref={(el) => { boxes.current[i] = el; }} style={{ width: "100%", minHeight: HEIGHT }} />
        </div>
      ))}
    </div>
  );
}
