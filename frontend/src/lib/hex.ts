/** Hexadecimal notation as EtherCAT configurators write it: `607Ah`, `607Ah:00h`, `00000402h`. */

/** `0x607a` → `607A` (zero-padded to `digits`). */
export function hex(n: number, digits = 4): string {
  return (n >>> 0).toString(16).toUpperCase().padStart(digits, "0");
}

/** `0x607a` → `607Ah`. */
export function hexH(n: number, digits = 4): string {
  return `${hex(n, digits)}h`;
}

/** An object or PDO entry: `607Ah:00h`; padding (index 0) is `—`. */
export function objKey(index: number, subindex: number): string {
  return index === 0 ? "—" : `${hex(index)}h:${hex(subindex, 2)}h`;
}

/** A bit offset as `bytes.bits` (`34` → `4.2`). */
export function byteBits(bitOffset: number): string {
  return `${Math.floor(bitOffset / 8)}.${bitOffset % 8}`;
}

/** A size in bits as bytes and bits (`16` → `2 B`, `1` → `1 bit`, `12` → `1 B 4 bit`). */
export function sizeText(bits: number): string {
  const bytes = Math.floor(bits / 8);
  const rest = bits % 8;
  if (bytes === 0) return `${rest} bit`;
  return rest ? `${bytes} B ${rest} bit` : `${bytes} B`;
}

/** `"0a1b"` → `[10, 27]` (an odd trailing digit is dropped). */
export function hexBytes(s: string): number[] {
  const out: number[] = [];
  for (let i = 0; i + 1 < s.length; i += 2) out.push(parseInt(s.slice(i, i + 2), 16));
  return out;
}
