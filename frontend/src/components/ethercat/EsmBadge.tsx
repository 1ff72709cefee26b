import { Badge, Tooltip } from "@mantine/core";
import type { EsmState } from "../../api/types";

const DESCRIPTION: Record<EsmState, string> = {
  Init: "Init: no communication (cable, power or start-up error)",
  PreOp: "Pre-Operational: mailbox only, no process data",
  Boot: "Bootstrap: firmware update mode",
  SafeOp: "Safe-Operational: inputs valid, outputs held safe",
  Op: "Operational: process data exchanged every cycle",
};

/** Mantine colour of an EtherCAT state machine state: Op green, SafeOp/PreOp amber, Init red. */
export function esmColor(state: EsmState | string): string {
  switch (state) {
    case "Op":
      return "green";
    case "SafeOp":
    case "PreOp":
      return "orange";
    case "Init":
      return "red";
    default:
      return "gray";
  }
}

/** The slave's ESM state as a coloured badge; `data-state` carries the state for scripts. */
export function EsmBadge({ state, testId, size = "sm" }: { state: EsmState; testId?: string; size?: "xs" | "sm" }) {
  return (
    <Tooltip label={DESCRIPTION[state] ?? state} openDelay={300}>
      <Badge
        size={size}
        color={esmColor(state)}
        variant={state === "Op" ? "light" : "filled"}
        style={{ textTransform: "none", flex: "none" }}
        leftSection={<span className="esm-dot" />}
        data-testid={testId}
        data-state={state}
      >
        {state}
      </Badge>
    </Tooltip>
  );
}
