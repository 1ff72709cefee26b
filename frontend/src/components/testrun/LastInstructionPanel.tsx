import { Group, Text } from "@mantine/core";
import { useAxisCommands } from "../../hooks/useLive";
import { Led } from "../common/Led";
import { Panel } from "../common/Panel";

/** Outputs of the last one-shot instruction issued on this axis (frozen once the instance was removed). */
export function LastInstructionPanel({ axis }: { axis: string }) {
  const { last } = useAxisCommands(axis);
  const o = last?.outputs ?? {};
  const flag = (name: string) => o[name] === true;
  const errorId = typeof o.ErrorID === "string" ? o.ErrorID : "0000";
  return (
    <Panel
      title="Last instruction"
      testId="last-instruction"
      right={
        last ? (
          <Text size="xs" ff="monospace" tt="none" fw={500} c="dark" data-testid="last-fb-type">
            {last.type} #{last.id}
            {last.gone ? " (removed)" : ""}
          </Text>
        ) : undefined
      }
    >
      {last ? (
        <Group gap={14} wrap="wrap">
          <Led label="Busy" on={flag("Busy")} color="blue" testId="fb-busy" />
          {"Active" in o && <Led label="Active" on={flag("Active")} color="blue" testId="fb-active" />}
          {"Done" in o && <Led label="Done" on={flag("Done")} color="teal" testId="fb-done" />}
          {"InVelocity" in o && <Led label="InVelocity" on={flag("InVelocity")} color="teal" testId="fb-invelocity" />}
          {"CommandAborted" in o && (
            <Led label="CommandAborted" on={flag("CommandAborted")} color="orange" testId="fb-aborted" />
          )}
          {"Failure" in o && <Led label="Failure" on={flag("Failure")} color="orange" testId="fb-failure" />}
          <Led label="Error" on={flag("Error")} color="red" testId="fb-error" />
          <Text size="xs" c={errorId === "0000" ? "dimmed" : "red"}>
            ErrorID{" "}
            <Text span className="num" fw={600} data-testid="fb-errorid">
              {errorId}
            </Text>
          </Text>
        </Group>
      ) : (
        <Text size="xs" c="dimmed">
          No instruction issued from this tab yet.
        </Text>
      )}
    </Panel>
  );
}
