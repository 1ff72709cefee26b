/**
 * PDO configuration rules the studio can check itself before the controller does (the controller's check in
 * fieldbus/pdo.py stays authoritative): exclusions, mandatory PDOs, entry counts, sync manager sizes, bit lengths.
 */
import type { DeviceDescription, PdoOut, SlaveOut } from "../api/types";
import { hexH } from "./hex";

export type Dir = "rx" | "tx";

export const DIRS: readonly Dir[] = ["rx", "tx"];

/** RxPDOs are 1600h–17FFh, TxPDOs 1A00h–1BFFh. */
export function dirOfPdo(index: number): Dir {
  return index < 0x1a00 ? "rx" : "tx";
}

export interface EntryLike {
  index: number;
  subindex: number;
  bit_len: number;
}

export interface ObjectInfo {
  name: string;
  data_type: string;
  bit_len: number;
  /** It may be mapped into RxPDOs ("R") and/or TxPDOs ("T"). */
  mapping: string;
}

export const objId = (index: number, subindex: number): string => `${index}:${subindex}`;

/**
 * Name, type and size of the objects of a device: its dictionary, completed by the entries of its PDOs (an object
 * that a PDO of a direction lists may be mapped in that direction, as the controller's check has it).
 */
export function objectTable(slave: SlaveOut, device: DeviceDescription | null): Map<string, ObjectInfo> {
  const out = new Map<string, ObjectInfo>();
  for (const o of device?.objects ?? []) {
    out.set(objId(o.index, o.subindex), {
      name: o.name ?? "",
      data_type: o.data_type ?? "",
      bit_len: o.bit_len ?? 0,
      mapping: (o.pdo_mapping ?? "").toUpperCase(),
    });
  }
  const sources = [
    ["R", device?.rx_pdos ?? []],
    ["T", device?.tx_pdos ?? []],
    ["R", slave.rx_pdos],
    ["T", slave.tx_pdos],
  ] as const;
  for (const [dir, pdos] of sources) {
    for (const p of pdos) {
      for (const e of p.entries ?? []) {
        if (e.index === 0) continue;
        const k = objId(e.index, e.subindex);
        const have = out.get(k);
        if (!have) {
          out.set(k, { name: e.name ?? "", data_type: e.data_type ?? "", bit_len: e.bit_len, mapping: dir });
        } else if (!have.mapping.includes(dir)) {
          out.set(k, { ...have, mapping: have.mapping + dir, bit_len: have.bit_len || e.bit_len });
        }
      }
    }
  }
  return out;
}

export function bitsOf(entries: readonly EntryLike[]): number {
  return entries.reduce((n, e) => n + e.bit_len, 0);
}

/** The assigned PDO that excludes `pdo` (either PDO may name the other), or null. */
export function excludedBy(pdo: PdoOut, assigned: readonly number[], pdos: readonly PdoOut[]): number | null {
  for (const idx of assigned) {
    if (idx === pdo.index) continue;
    if (pdo.excludes.includes(idx)) return idx;
    const other = pdos.find((p) => p.index === idx);
    if (other?.excludes.includes(pdo.index)) return idx;
  }
  return null;
}

/** The largest process image of a direction the device's sync manager takes [bytes] (1024 without one). */
export function smLimit(device: DeviceDescription | null, dir: Dir): number {
  const sm = device?.sync_managers?.find((s) => s.type === (dir === "rx" ? "Outputs" : "Inputs"));
  return sm?.max_size ?? 1024;
}

export interface DraftLike {
  rx_assign: readonly number[];
  tx_assign: readonly number[];
  entries: Readonly<Record<number, readonly EntryLike[]>>;
}

export function assignOf(d: DraftLike, dir: Dir): readonly number[] {
  return dir === "rx" ? d.rx_assign : d.tx_assign;
}

/** Size of a direction's process image with this draft [bits]. */
export function imageBits(d: DraftLike, dir: Dir): number {
  return assignOf(d, dir).reduce((n, idx) => n + bitsOf(d.entries[idx] ?? []), 0);
}

/** Where each assigned PDO starts in its direction's image [bit]. */
export function pdoStarts(d: DraftLike, dir: Dir): Map<number, number> {
  const out = new Map<number, number>();
  let bit = 0;
  for (const idx of assignOf(d, dir)) {
    out.set(idx, bit);
    bit += bitsOf(d.entries[idx] ?? []);
  }
  return out;
}

/** Problems that make Apply pointless (the controller would refuse them); empty when the draft may be sent. */
export function draftProblems(d: DraftLike, slave: SlaveOut, device: DeviceDescription | null): string[] {
  const out: string[] = [];
  const maxEntries = device?.max_entries_per_pdo ?? 254;
  for (const dir of DIRS) {
    const pdos = dir === "rx" ? slave.rx_pdos : slave.tx_pdos;
    const assigned = assignOf(d, dir);
    for (const p of pdos) {
      if (p.mandatory && !assigned.includes(p.index)) out.push(`${hexH(p.index)} is mandatory`);
      const ex = assigned.includes(p.index) ? excludedBy(p, assigned, pdos) : null;
      if (ex !== null && p.index < ex) out.push(`${hexH(p.index)} and ${hexH(ex)} exclude each other`);
    }
    for (const idx of assigned) {
      const entries = d.entries[idx] ?? [];
      if (entries.length > maxEntries) out.push(`${hexH(idx)} has ${entries.length} entries (at most ${maxEntries})`);
      if (entries.some((e) => !Number.isInteger(e.bit_len) || e.bit_len < 1 || e.bit_len > 64)) {
        out.push(`${hexH(idx)}: bit lengths are 1–64`);
      }
    }
    const bytes = Math.ceil(imageBits(d, dir) / 8);
    const limit = smLimit(device, dir);
    if (bytes > limit) out.push(`the ${dir === "rx" ? "outputs" : "inputs"} are ${bytes} bytes (sync manager: at most ${limit})`);
  }
  return out;
}
