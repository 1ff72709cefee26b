import { Box, Group, SimpleGrid, Stack, Text } from "@mantine/core";
import type { ReactNode } from "react";
import type { AxisVariables } from "../../api/types";
import { useAxisCommands, useAxisVars, useErrorInfo, useFb } from "../../hooks/useLive";
import { type AxisUnits, STATUS_FLAGS } from "../../lib/format";
import { Led } from "../common/Led";
import { Num } from "../common/Num";
import { Panel } from "../common/Panel";

function Value({ label, children }: { label: string; children: ReactNode }) {
  return (
    <Stack gap={0} align="flex-end">
      <Text size="10px" c="dimmed" tt="uppercase" style={{ letterSpacing: "0.03em", whiteSpace: "nowrap" }}>
        {label}
      </Text>
      <Text size="sm" fw={500} component="div">
        {children}
      </Text>
    </Stack>
  );
}

/** Command/actual position and velocity, following error, acc./dec., torque and direction. */
export function PositionPanel({ axis, units }: { axis: string; units: AxisUnits }) {
  const v = useAxisVars(axis);
  if (!v) return null;
  return (
    <Panel
      title="Position and velocity"
      testId="position-panel"
      right={
        <Group gap={10} wrap="nowrap">
          <Led label="Dir. Posi" on={v.Dir.Posi} color="blue" testId="dir-posi" />
          <Led label="Dir. Nega" on={v.Dir.Nega} color="blue" testId="dir-nega" />
        </Group>
      }
    >
      <SimpleGrid cols={3} spacing={8} verticalSpacing={6}>
        <Value label="Command position">
          <Num value={v.Cmd.Pos} unit={units.pos} testId="cmd-pos" />
        </Value>
        <Value label="Actual position">
          <Num value={v.Act.Pos} unit={units.pos} testId="act-pos" />
        </Value>
        <Value label="Following error">
          <Num value={v.Cmd.Pos - v.Act.Pos} unit={units.pos} testId="following-error" />
        </Value>
        <Value label="Command velocity">
          <Num value={v.Cmd.Vel} unit={units.vel} testId="cmd-vel" />
        </Value>
        <Value label="Actual velocity">
          <Num value={v.Act.Vel} unit={units.vel} testId="act-vel" />
        </Value>
        <Value label="Command acc./dec.">
          <Num value={v.Cmd.AccDec} decimals={1} unit={units.acc} testId="cmd-accdec" />
        </Value>
        <Value label="Command torque">
          <Num value={v.Cmd.Trq} decimals={1} unit="%" testId="cmd-trq" />
        </Value>
        <Value label="Actual torque">
          <Num value={v.Act.Trq} decimals={1} unit="%" testId="act-trq" />
        </Value>
      </SimpleGrid>
    </Panel>
  );
}

function FlagRow({ label, children }: { label: string; children: ReactNode }) {
  return (
    <Group gap={8} wrap="nowrap" align="flex-start">
      <Text size="10px" c="dimmed" tt="uppercase" w={62} pt={1} style={{ flex: "none", letterSpacing: "0.03em" }}>
        {label}
      </Text>
      <Group gap="6px 12px" wrap="wrap" style={{ flex: 1 }}>
        {children}
      </Group>
    </Group>
  );
}

const STATE_COLORS: Record<string, string> = { ErrorStop: "red", Stopping: "orange", Disabled: "gray", Standstill: "teal" };
const DETAILS = ["Idle", "InPosWaiting", "Homed", "InHome", "VelLimit"] as const;
const DRV = [
  "ServoOn",
  "Ready",
  "MainPower",
  "P_OT",
  "N_OT",
  "HomeSw",
  "Home",
  "ImdStop",
  "Latch1",
  "Latch2",
  "DrvAlarm",
  "DrvWarning",
  "ILA",
  "CSP",
  "CSV",
  "CST",
] as const;

function drvColor(name: (typeof DRV)[number]): string {
  if (name === "DrvAlarm" || name === "P_OT" || name === "N_OT" || name === "ImdStop") return "red";
  if (name === "HomeSw" || name === "Home" || name === "Latch1" || name === "Latch2") return "violet";
  if (name === "DrvWarning" || name === "ILA") return "yellow";
  return "teal";
}

/** Status, Details and DrvStatus flags of _sAXIS_REF. */
export function StatusPanel({ axis }: { axis: string }) {
  const v: AxisVariables | undefined = useAxisVars(axis);
  if (!v) return null;
  return (
    <Panel title="Axis variable flags" testId="status-panel">
      <Stack gap={6}>
        <FlagRow label="Status">
          {STATUS_FLAGS.map((f) => (
            <Led key={f} label={f} on={v.Status[f]} color={STATE_COLORS[f] ?? "blue"} testId={`status-${f}`} />
          ))}
          <Led label="Ready" on={v.Status.Ready} color="teal" testId="status-Ready" />
        </FlagRow>
        <FlagRow label="Details">
          {DETAILS.map((f) => (
            <Led key={f} label={f} on={v.Details[f]} color="blue" testId={`details-${f}`} />
          ))}
        </FlagRow>
        <FlagRow label="Drive">
          {DRV.map((f) => (
            <Led key={f} label={f} on={v.DrvStatus[f]} color={drvColor(f)} testId={`drv-${f}`} />
          ))}
        </FlagRow>
      </Stack>
    </Panel>
  );
}

/** An error or observation code in a framed box. */
function CodeBox({ label, code, active, color, testId }: {
  label: string;
  code: string;
  active: boolean;
  color: string;
  testId: string;
}) {
  return (
    <Box
      px={8}
      py={2}
      w={64}
      style={{
        borderRadius: 4,
        background: active ? `var(--mantine-color-${color}-0)` : "var(--mantine-color-gray-0)",
        border: `1px solid var(--mantine-color-${active ? `${color}-4` : "gray-3"})`,
        flex: "none",
      }}
    >
      <Text size="10px" c="dimmed" tt="uppercase">
        {label}
      </Text>
      <Text size="md" fw={700} className="num" c={active ? `${color}.8` : "dimmed"} data-testid={testId}>
        {code}
      </Text>
    </Box>
  );
}

/**
 * The axis error: the minor fault of the axis (MFaultLvl) or, when the axis has none, the ErrorID of an instruction
 * of this axis that ended with Error; and the observation (Obsr, warnings such as 6460 following error warning).
 * Meanings come from the ErrorID catalogue (GET /api/v1/errors).
 */
export function AxisErrorPanel({ axis }: { axis: string }) {
  const fault = useAxisVars(axis)?.MFaultLvl;
  const obsr = useAxisVars(axis)?.Obsr;
  const cmds = useAxisCommands(axis);
  const jog = useFb(cmds.jogId);
  const power = useFb(cmds.powerId);
  const lastErr = cmds.last?.outputs.Error === true ? cmds.last.outputs.ErrorID : undefined;

  let code = "0000";
  if (fault?.Active) code = fault.Code;
  else if (typeof lastErr === "string") code = lastErr;
  else if (jog?.outputs.Error === true && typeof jog.outputs.ErrorID === "string") code = jog.outputs.ErrorID;
  else if (power?.outputs.Error === true && typeof power.outputs.ErrorID === "string") code = power.outputs.ErrorID;
  code = code.toUpperCase();
  const info = useErrorInfo(code === "0000" ? null : code);
  const hasError = code !== "0000";
  const meaning = hasError ? (info ? `${info.name}. ${info.correction}` : "Unknown ErrorID (not in the error catalogue)") : "";
  const obsrCode = (obsr?.Active ? obsr.Code : "0000").toUpperCase();
  const obsrInfo = useErrorInfo(obsr?.Active ? obsrCode : null);

  return (
    <Panel
      title="Axis error and observation"
      testId="error-panel"
      right={
        <Group gap={10} wrap="nowrap">
          <Led label="MFaultLvl" on={fault?.Active ?? false} color="red" testId="mfault-active" />
          <Led label="Obsr" on={obsr?.Active ?? false} color="yellow" testId="obsr-active" />
        </Group>
      }
    >
      <Stack gap={6}>
        <Group gap={10} wrap="nowrap" align="flex-start">
          <CodeBox label="ErrorID" code={code} active={hasError} color="red" testId="error-id" />
          <Stack gap={2} style={{ minWidth: 0, flex: 1 }}>
            <Text size="xs" c={hasError ? "red.9" : "dimmed"} data-testid="error-meaning" style={{ minHeight: 16 }}>
              {meaning}
            </Text>
            {!hasError && (
              <Text size="xs" c="dimmed">
                No error.
              </Text>
            )}
            {hasError && info && (
              <Text size="10px" c="dimmed">
                Event code {info.event_code} · {info.level} · cause: {info.cause}
              </Text>
            )}
          </Stack>
        </Group>
        <Group gap={10} wrap="nowrap" align="flex-start">
          <CodeBox label="Obsr" code={obsrCode} active={obsr?.Active ?? false} color="yellow" testId="obsr-code" />
          <Stack gap={2} style={{ minWidth: 0, flex: 1 }}>
            <Text size="xs" c={obsr?.Active ? "yellow.9" : "dimmed"} data-testid="obsr-meaning" style={{ minHeight: 16 }}>
              {obsr?.Active
                ? obsrInfo
                  ? `${obsrInfo.name}. ${obsrInfo.correction}`
                  : "Unknown observation code (not in the error catalogue)"
                : "No observation (warning)."}
            </Text>
            {obsr?.Active && obsrInfo && (
              <Text size="10px" c="dimmed">
                Event code {obsrInfo.event_code} · {obsrInfo.level} · cause: {obsrInfo.cause}
              </Text>
            )}
          </Stack>
        </Group>
      </Stack>
    </Panel>
  );
}
