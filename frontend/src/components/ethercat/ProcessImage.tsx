import { Stack, Text } from "@mantine/core";
import { useState } from "react";
import { api, unwrap } from "../../api/client";
import type { ImageOut } from "../../api/types";
import { hex, hexBytes } from "../../lib/hex";
import { usePoll } from "../../lib/usePoll";
import type { Dir } from "../../lib/pdo";
import { Panel } from "../common/Panel";

/** Bits of one direction's image to highlight (the selected entry). */
export interface ImageHighlight {
  dir: Dir;
  bit: number;
  bits: number;
}

const PER_ROW = 8;

interface Frames {
  image: ImageOut | null;
  /** The image before, to mark the bytes that changed. */
  prev: ImageOut | null;
}

function useImage(node: number, intervalMs: number): Frames & { error: string | null } {
  const [frames, setFrames] = useState<Frames>({ image: null, prev: null });
  const { error } = usePoll(
    () => unwrap(api.GET("/api/v1/ethercat/slaves/{address}/image", { params: { path: { address: node } } })),
    { intervalMs, deps: [node], onData: (img) => setFrames((f) => ({ image: img, prev: f.image })) },
  );
  return { ...frames, error };
}

interface DumpProps {
  dir: Dir;
  hexText: string;
  prevHex: string;
  highlight: ImageHighlight | null;
  testId: string;
}

function Dump({ dir, hexText, prevHex, highlight, testId }: DumpProps) {
  const bytes = hexBytes(hexText);
  const before = hexBytes(prevHex);
  const hl = highlight?.dir === dir ? highlight : null;
  const lo = hl ? Math.floor(hl.bit / 8) : -1;
  const hi = hl ? Math.ceil((hl.bit + hl.bits) / 8) : -1;
  const rows: number[][] = [];
  for (let i = 0; i < bytes.length; i += PER_ROW) rows.push(bytes.slice(i, i + PER_ROW));
  return (
    <div className="hex-dump" data-testid={testId} data-bytes={bytes.length}>
      <div className="hex-row hex-head">
        <span className="hex-off" />
        {Array.from({ length: PER_ROW }, (_, i) => (
          <span key={i} className="hex-b">{hex(i, 2)}</span>
        ))}
      </div>
      {rows.length === 0 && <Text size="xs" c="dimmed">No bytes.</Text>}
      {rows.map((r, ri) => (
        <div key={ri} className="hex-row">
          <span className="hex-off">{hex(ri * PER_ROW, 4)}</span>
          {r.map((b, i) => {
            const k = ri * PER_ROW + i;
            return (
              <span key={i} className="hex-b" data-hl={k >= lo && k < hi ? "true" : undefined}
                data-changed={before.length === bytes.length && before[k] !== b ? "true" : undefined}>
                {hex(b, 2)}
              </span>
            );
          })}
        </div>
      ))}
    </div>
  );
}

/** The slave's process image as it last travelled on the wire, refreshed twice a second. */
export function ProcessImage({ node, highlight, note }: { node: number; highlight: ImageHighlight | null; note: string }) {
  const { image, prev, error } = useImage(node, 500);
  return (
    <Panel
      testId="pdo-image"
      title="Process image"
      right={
        <Text size="11px" tt="none" c="dimmed" className="num" data-testid="pdo-image-cycle">
          {error ? <Text span c="red.7" size="11px">{error}</Text> : image ? `cycle ${image.cycle}` : "…"}
        </Text>
      }
    >
      <Stack gap={8}>
        <div>
          <Text size="11px" fw={600} c="gray.7" mb={2}>
            Outputs (master → slave) · {image ? image.rx_hex.length / 2 : "—"} bytes
          </Text>
          <Dump dir="rx" hexText={image?.rx_hex ?? ""} prevHex={prev?.rx_hex ?? ""} highlight={highlight} testId="pdo-image-rx" />
        </div>
        <div>
          <Text size="11px" fw={600} c="gray.7" mb={2}>
            Inputs (slave → master) · {image ? image.tx_hex.length / 2 : "—"} bytes
          </Text>
          <Dump dir="tx" hexText={image?.tx_hex ?? ""} prevHex={prev?.tx_hex ?? ""} highlight={highlight} testId="pdo-image-tx" />
        </div>
        <Text size="10px" c="dimmed" lh={1.3} data-testid="pdo-image-note">
          {note}
        </Text>
      </Stack>
    </Panel>
  );
}
