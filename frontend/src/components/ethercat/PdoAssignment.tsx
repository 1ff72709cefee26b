import { Badge, Checkbox, Text, Tooltip } from "@mantine/core";
import { IconBan, IconLock } from "@tabler/icons-react";
import type { DeviceDescription, PdoOut, SlaveOut } from "../../api/types";
import { hex, hexH } from "../../lib/hex";
import { type Dir, assignOf, bitsOf, dirOfPdo, excludedBy, imageBits, smLimit } from "../../lib/pdo";
import { type PdoEditor, selectPdo, setAssigned } from "../../store/pdoEditor";
import { Panel } from "../common/Panel";

/** Why the checkbox of a PDO cannot be changed, or null. */
function lockReason(p: PdoOut, assigned: readonly number[], pdos: readonly PdoOut[]): string | null {
  const on = assigned.includes(p.index);
  if (on && p.mandatory) return `${hexH(p.index)} is mandatory: it must stay assigned`;
  if (!on) {
    const by = excludedBy(p, assigned, pdos);
    if (by !== null) return `Excluded by ${hexH(by)}: unassign ${hexH(by)} first`;
  }
  return null;
}

function AssignRow({ node, p, ed, pdos, order }: {
  node: number;
  p: PdoOut;
  ed: PdoEditor;
  pdos: readonly PdoOut[];
  order: readonly number[];
}) {
  const dir = dirOfPdo(p.index);
  const assigned = assignOf(ed.draft, dir);
  const on = assigned.includes(p.index);
  const locked = lockReason(p, assigned, pdos);
  const issues = ed.issues.filter(
    (i) => (i.target.kind === "assign" && i.target.pdo === p.index) || (i.target.kind === "pdo" && i.target.pdo === p.index),
  );
  const entryIssues = ed.issues.filter((i) => i.target.kind === "entry" && i.target.pdo === p.index).length;
  const bits = bitsOf(ed.draft.entries[p.index] ?? []);
  const id = hex(p.index);
  return (
    <>
      <div
        className="pdo-assign-row"
        data-selected={ed.selected === p.index ? "true" : undefined}
        data-assigned={on ? "true" : "false"}
        data-invalid={issues.length || entryIssues ? "true" : undefined}
        onClick={() => selectPdo(node, p.index)}
        data-testid={`pdo-assign-${id}`}
      >
        <Tooltip label={locked ?? ""} disabled={!locked} openDelay={150} withinPortal>
          <span onClick={(e) => e.stopPropagation()} style={{ display: "inline-flex" }} data-testid={`pdo-lock-${id}`}
            data-locked={locked ? "true" : "false"} title={locked ?? undefined}>
            <Checkbox
              size="xs"
              checked={on}
              disabled={locked !== null || ed.applying}
              onChange={(e) => setAssigned(node, p.index, e.currentTarget.checked, order)}
              aria-label={`Assign ${hexH(p.index)}`}
              data-testid={`pdo-check-${id}`}
            />
          </span>
        </Tooltip>
        <span className="num pdo-index">{id}h</span>
        <Text size="xs" truncate="end" title={p.name} style={{ flex: 1, minWidth: 0 }}>
          {p.name || "—"}
        </Text>
        {p.fixed && (
          <Tooltip label="Fixed: its entries cannot be changed" openDelay={200}>
            <IconLock size={12} color="var(--mantine-color-gray-6)" style={{ flex: "none" }} />
          </Tooltip>
        )}
        {p.mandatory && (
          <Tooltip label="Mandatory: must be assigned" openDelay={200}>
            <Badge size="xs" variant="outline" color="gray" radius="xs" px={3}>M</Badge>
          </Tooltip>
        )}
        {p.excludes.length > 0 && (
          <Tooltip label={`Excludes ${p.excludes.map((x) => hexH(x)).join(", ")}: they cannot be assigned together`}
            openDelay={200}>
            <IconBan size={12} color="var(--mantine-color-gray-5)" style={{ flex: "none" }}
              data-testid={`pdo-excludes-${id}`} />
          </Tooltip>
        )}
        <Text size="11px" className="num" c={on ? "dark" : "dimmed"} w={44} ta="right" style={{ flex: "none" }}>
          {Math.ceil(bits / 8)} B
        </Text>
      </div>
      {issues.map((i, k) => (
        <Text key={k} size="11px" c="red.7" className="pdo-row-error" data-testid={`pdo-assign-error-${id}`} role="alert">
          {i.msg}
        </Text>
      ))}
    </>
  );
}

/** The PDO assignment of one direction (1C12h RxPDOs / 1C13h TxPDOs) as a checkbox list; a row selects the PDO. */
export function PdoAssignment({ node, dir, slave, device, ed }: {
  node: number;
  dir: Dir;
  slave: SlaveOut;
  device: DeviceDescription | null;
  ed: PdoEditor;
}) {
  const pdos = dir === "rx" ? slave.rx_pdos : slave.tx_pdos;
  const order = pdos.map((p) => p.index);
  const bytes = Math.ceil(imageBits(ed.draft, dir) / 8);
  const limit = smLimit(device, dir);
  const listIssues = ed.issues.filter((i) => i.target.kind === "assign" && i.target.dir === dir && i.target.pdo === null);
  return (
    <Panel
      testId={`pdo-assignment-${dir}`}
      bodyPadding={4}
      title={
        <>
          {dir === "rx" ? "Outputs · RxPDOs " : "Inputs · TxPDOs "}
          <span style={{ textTransform: "none", fontWeight: 500 }}>{dir === "rx" ? "1C12h" : "1C13h"}</span>
        </>
      }
      right={
        <Tooltip label={`Sync manager ${dir === "rx" ? "outputs" : "inputs"}: at most ${limit} bytes`}>
          <Text size="11px" fw={600} tt="none" className="num" c={bytes > limit ? "red.7" : "gray.7"}
            data-testid={`pdo-total-${dir}`}>
            {bytes} bytes
          </Text>
        </Tooltip>
      }
    >
      {pdos.map((p) => (
        <AssignRow key={p.index} node={node} p={p} ed={ed} pdos={pdos} order={order} />
      ))}
      {listIssues.map((i, k) => (
        <Text key={k} size="11px" c="red.7" className="pdo-row-error" data-testid={`pdo-assign-error-${dir}`} role="alert">
          {i.msg}
        </Text>
      ))}
    </Panel>
  );
}
