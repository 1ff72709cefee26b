import { Badge, Button, Group, Stack, Text, Tooltip } from "@mantine/core";
import { IconHandStop, IconHome, IconPlayerStop, IconPower, IconRefresh } from "@tabler/icons-react";
import { useErrorInfo, useLive } from "../../hooks/useLive";
import { issue } from "../../store/commands";
import {
  type GroupInfo,
  disableGroup,
  enableGroup,
  immediateStopGroup,
  resetGroup,
  setGroupServo,
  stopGroup,
  useGroupCommands,
} from "../../store/groupCommands";
import { Led } from "../common/Led";

export function groupStateColor(state: string): string {
  if (state === "ErrorStop") return "red";
  if (state === "Disabled") return "gray";
  if (state === "Standby") return "teal";
  if (state === "Stopping") return "orange";
  return "blue";
}

/** A code with the manual's name of the error (from the error catalog). */
export function ErrorCode({ code, testId }: { code: string; testId?: string }) {
  const info = useErrorInfo(code);
  if (!code || code === "0000") return null;
  return (
    <Text size="xs" c="red" data-testid={testId}>
      <Text span ff="monospace" fw={700}>
        {code}
      </Text>
      {info ? ` ${info.name}` : ""}
    </Text>
  );
}

/** State of the group, its composition axes' servo, and the state buttons (all through /api/v1/fb). */
export function GroupControls({ group, compact = false }: { group: GroupInfo; compact?: boolean }) {
  const on = useLive((s) => group.axes.filter((a) => s.axes[a]?.Status?.Disabled === false).length);
  const unhomed = useLive((s) => group.axes.filter((a) => s.axes[a]?.Details?.Homed === false).length);
  const allOn = on === group.axes.length;
  const anyOn = on > 0;
  const enabled = group.state !== "Disabled";
  const size = compact ? "compact-xs" : "xs";
  return (
    <Stack gap={6} data-testid={`group-controls-${group.name}`}>
      <Group gap={8} wrap="nowrap" justify="space-between">
        <Group gap={6} wrap="nowrap">
          <Text size="xs" c="dimmed">
            State
          </Text>
          <Badge color={groupStateColor(group.state)} variant="light" size="sm" tt="none"
            data-testid={`group-state-${group.name}`}>
            {group.state}
          </Badge>
        </Group>
        <Group gap={8} wrap="nowrap">
          <Led label="Servo" on={allOn} color="teal" />
          <Led label="Ready" on={group.ready} color="teal" />
        </Group>
      </Group>
      <ErrorCode code={group.error_code} testId={`group-error-${group.name}`} />
      <Group gap={4} wrap="wrap">
        <Tooltip label={`MC_Power of ${group.axes.join(", ")}`} openDelay={400}>
          <Button size={size} variant={allOn ? "filled" : "default"} color="teal" leftSection={<IconPower size={13} />}
            data-testid={`group-servo-${group.name}`} onClick={() => void setGroupServo(group.axes, !anyOn)}>
            {anyOn ? "Servo OFF" : "Servo ON"}
          </Button>
        </Tooltip>
        {unhomed > 0 && (
          <Tooltip label={`MC_Home of ${group.axes.join(", ")} (group disabled, servo ON): group motion needs a defined home`}
            openDelay={400} multiline w={260}>
            <Button size={size} variant="light" color="yellow" leftSection={<IconHome size={13} />}
              disabled={!allOn || enabled} data-testid={`group-home-${group.name}`}
              onClick={() => group.axes.forEach((a) => void issue(a, "MC_Home", {}))}>
              Home axes
            </Button>
          </Tooltip>
        )}
        <Tooltip label={enabled ? "MC_GroupDisable" : "MC_GroupEnable"} openDelay={400}>
          <Button size={size} variant="default" data-testid={`group-enable-${group.name}`}
            onClick={() => void (enabled ? disableGroup(group.name) : enableGroup(group.name))}>
            {enabled ? "Disable" : "Enable"}
          </Button>
        </Tooltip>
        <Tooltip label="MC_GroupStop (deceleration along the path; 0 for a robot = immediate)" openDelay={400}>
          <Button size={size} variant="default" color="orange" leftSection={<IconPlayerStop size={13} />}
            data-testid={`group-stop-${group.name}`}
            onClick={() => void stopGroup(group.name, group.kinematics ? 0 : 2000)}>
            Stop
          </Button>
        </Tooltip>
        <Tooltip label="MC_GroupImmediateStop (ErrorStop 5486)" openDelay={400}>
          <Button size={size} variant="light" color="red" leftSection={<IconHandStop size={13} />}
            data-testid={`group-immediate-stop-${group.name}`} onClick={() => void immediateStopGroup(group.name)}>
            Immediate stop
          </Button>
        </Tooltip>
        <Tooltip label="MC_GroupReset" openDelay={400}>
          <Button size={size} variant="default" leftSection={<IconRefresh size={13} />}
            data-testid={`group-reset-${group.name}`} onClick={() => void resetGroup(group.name)}>
            Reset
          </Button>
        </Tooltip>
      </Group>
    </Stack>
  );
}

/** Outputs of the last group instruction issued from the studio, with the ErrorID and its name. */
export function LastGroupInstruction({ group }: { group: string }) {
  const { last } = useGroupCommands(group);
  if (!last) return null;
  const o = last.outputs;
  const flag = (n: string) => o[n] === true;
  const errorId = typeof o.ErrorID === "string" ? o.ErrorID : "0000";
  return (
    <Stack gap={2} data-testid={`group-last-${group}`}>
      <Text size="xs" ff="monospace" c="dimmed">
        {last.type} #{last.id}
        {last.gone ? " (removed)" : ""}
      </Text>
      <Group gap={10} wrap="wrap">
        <Led label="Busy" on={flag("Busy")} color="blue" />
        {"Active" in o && <Led label="Active" on={flag("Active")} color="blue" />}
        {"Done" in o && <Led label="Done" on={flag("Done")} color="teal" />}
        {"InPosition" in o && <Led label="InPosition" on={flag("InPosition")} color="teal" />}
        {"CommandAborted" in o && <Led label="Aborted" on={flag("CommandAborted")} color="orange" />}
        <Led label="Error" on={flag("Error")} color="red" />
      </Group>
      <ErrorCode code={errorId} testId={`group-last-error-${group}`} />
    </Stack>
  );
}
