import { Box, Group, Text } from "@mantine/core";
import { useEffect, useRef, useState } from "react";
import uPlot from "uplot";
import type { TraceData } from "../../store/trace";

const COLORS = ["#1c7ed6", "#e8590c", "#2f9e44", "#ae3ec9", "#f08c00", "#0c8599", "#e03131", "#5c940d", "#3b5bdb",
  "#c2255c"];
const FONT = "11px system-ui, sans-serif";

/** The series' shape (labels and units): the chart is rebuilt when it changes, else only its data are replaced. */
const signature = (d: TraceData): string => d.series.map((s) => `${s.label}[${s.unit}]`).join("|");

function fmt(v: number | null | undefined): string {
  if (v === null || v === undefined || Number.isNaN(v)) return "—";
  const a = Math.abs(v);
  return a !== 0 && (a < 1e-3 || a >= 1e6) ? v.toExponential(4) : v.toFixed(a < 10 ? 4 : a < 1000 ? 3 : 1);
}

function nearest(xs: number[], x: number): number {
  let lo = 0;
  let hi = xs.length - 1;
  if (hi < 0) return -1;
  while (hi - lo > 1) {
    const mid = (lo + hi) >> 1;
    if (xs[mid] <= x) lo = mid;
    else hi = mid;
  }
  return Math.abs(xs[lo] - x) <= Math.abs(xs[hi] - x) ? lo : hi;
}

interface Cursors {
  a: number | null;
  b: number | null;
}

function makeOptions(d: TraceData, width: number, height: number, cursors: React.MutableRefObject<Cursors>,
  onCursor: () => void, zoomed: React.MutableRefObject<boolean>,
  latest: React.MutableRefObject<TraceData | null>): uPlot.Options {
  const units = [...new Set(d.series.map((s) => s.unit || "value"))];
  const scales: uPlot.Scales = { x: { time: false } };
  for (const u of units) scales[`u:${u}`] = u === "bool" ? { range: [-0.1, 1.15] } : { auto: true };
  const axes: uPlot.Axis[] = [
    {
      font: FONT, size: 30, gap: 2, stroke: "#495057", grid: { stroke: "#e9ecef", width: 1 },
      ticks: { stroke: "#ced4da", width: 1, size: 4 }, values: (_u, splits) => splits.map((s) => `${+s.toFixed(6)} s`),
    },
    ...units.map((u, k): uPlot.Axis => {
      const first = d.series.findIndex((s) => (s.unit || "value") === u);
      return {
        scale: `u:${u}`, side: k % 2 === 0 ? 3 : 1, label: u, labelFont: FONT, labelSize: 14, font: FONT, size: 56,
        gap: 3, stroke: COLORS[first % COLORS.length], grid: { show: k === 0, stroke: "#e9ecef", width: 1 },
        ticks: { stroke: "#ced4da", width: 1, size: 4 },
      };
    }),
  ];
  const series: uPlot.Series[] = [
    { label: "t [s]", value: (_u, v) => (v === null ? "—" : `${v.toFixed(4)}`) },
    ...d.series.map((s, k): uPlot.Series => ({
      label: s.unit ? `${s.label} [${s.unit}]` : s.label, scale: `u:${s.unit || "value"}`,
      stroke: COLORS[k % COLORS.length], width: 1.4, paths: s.type === "REAL" ? undefined : uPlot.paths.stepped?.({ align: 1 }),
      value: (_u, v) => fmt(v),
    })),
  ];
  const vline = (u: uPlot, x: number | null, color: string, dash: number[], label: string) => {
    if (x === null || x < (u.scales.x.min ?? -Infinity) || x > (u.scales.x.max ?? Infinity)) return;
    const px = Math.round(u.valToPos(x, "x", true));
    const ctx = u.ctx;
    ctx.save();
    ctx.strokeStyle = color;
    ctx.setLineDash(dash);
    ctx.lineWidth = 1.5;
    ctx.beginPath();
    ctx.moveTo(px, u.bbox.top);
    ctx.lineTo(px, u.bbox.top + u.bbox.height);
    ctx.stroke();
    ctx.fillStyle = color;
    ctx.font = "bold 11px system-ui, sans-serif";
    ctx.fillText(label, px + 3, u.bbox.top + 12);
    ctx.restore();
  };
  return {
    width, height, pxAlign: 0, scales, axes, series,
    legend: { show: true, live: true },
    cursor: { drag: { x: true, y: false, setScale: true }, points: { size: 5 } },
    hooks: {
      draw: [
        (u) => {
          vline(u, latest.current?.trigger_time_s ?? null, "#e03131", [6, 4], "T");
          vline(u, cursors.current.a, "#1971c2", [], "A");
          vline(u, cursors.current.b, "#9c36b5", [], "B");
        },
      ],
      setSelect: [
        (u) => {
          if (u.select.width > 2) zoomed.current = true;
        },
      ],
      ready: [
        (u) => {
          let down: [number, number] | null = null;
          u.over.addEventListener("mousedown", (e) => (down = [e.clientX, e.clientY]));
          u.over.addEventListener("click", (e) => {
            if (!down || Math.abs(e.clientX - down[0]) > 3 || Math.abs(e.clientY - down[1]) > 3) return;
            const x = u.posToVal(u.cursor.left ?? 0, "x");
            if (e.shiftKey) cursors.current.b = x;
            else cursors.current.a = x;
            onCursor();
            u.redraw(false);
          });
          u.over.addEventListener("dblclick", () => {
            zoomed.current = false;
          });
        },
      ],
    },
  };
}

/**
 * The trace plot: one Y axis per unit, the trigger (T) as a dashed red line, drag to zoom (double-click resets),
 * click to place cursor A, shift-click for B; the readout below lists both cursors, Δt and the values there.
 */
export function TraceChart({ data }: { data: TraceData | null }) {
  const boxRef = useRef<HTMLDivElement>(null);
  const plotRef = useRef<uPlot | null>(null);
  const sigRef = useRef<string>("");
  const cursors = useRef<Cursors>({ a: null, b: null });
  const zoomed = useRef(false);
  const latest = useRef<TraceData | null>(null);
  const [cursorTick, setCursorTick] = useState(0);

  useEffect(() => {
    const box = boxRef.current;
    if (!box) return;
    const ro = new ResizeObserver(() => {
      const p = plotRef.current;
      if (p) p.setSize({ width: Math.max(300, box.clientWidth), height: Math.max(200, box.clientHeight - 60) });
    });
    ro.observe(box);
    return () => {
      ro.disconnect();
      plotRef.current?.destroy();
      plotRef.current = null;
      sigRef.current = "";
    };
  }, []);

  useEffect(() => {
    const box = boxRef.current;
    if (!box || !data) return;
    latest.current = data;
    const aligned: uPlot.AlignedData = [data.time_s, ...data.series.map((s) => s.values)];
    const sig = signature(data);
    if (plotRef.current && sig === sigRef.current) {
      plotRef.current.setData(aligned, !zoomed.current);
      return;
    }
    plotRef.current?.destroy();
    cursors.current = { a: null, b: null };
    zoomed.current = false;
    sigRef.current = sig;
    const opts = makeOptions(data, Math.max(300, box.clientWidth), Math.max(200, box.clientHeight - 60), cursors,
      () => setCursorTick((t) => t + 1), zoomed, latest);
    plotRef.current = new uPlot(opts, aligned, box);
  }, [data]);

  const { a, b } = cursors.current;
  void cursorTick;
  const at = (x: number | null, k: number): string => {
    if (x === null || !data) return "—";
    const i = nearest(data.time_s, x);
    return i < 0 ? "—" : fmt(data.series[k].values[i]);
  };
  return (
    <Box style={{ flex: 1, minHeight: 0, display: "flex", flexDirection: "column" }}>
      <div ref={boxRef} style={{ flex: 1, minHeight: 260, width: "100%" }} data-testid="trace-chart" />
      {data && (a !== null || b !== null) && (
        <Group gap="md" px={8} py={4} style={{ borderTop: "1px solid #e9ecef" }} data-testid="trace-cursors">
          <Text size="xs" c="blue.8">A {a !== null ? `${a.toFixed(4)} s` : "—"}</Text>
          <Text size="xs" c="grape.8">B {b !== null ? `${b.toFixed(4)} s` : "—"}</Text>
          {a !== null && b !== null && <Text size="xs" fw={600}>Δt {(b - a).toFixed(4)} s</Text>}
          {data.series.map((s, k) => (
            <Text size="xs" key={s.label} c="dimmed">
              {s.label}: {at(a, k)}
              {b !== null ? ` / ${at(b, k)}` : ""}
            </Text>
          ))}
        </Group>
      )}
    </Box>
  );
}
