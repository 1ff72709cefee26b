import { Button, Group, Text, TextInput, Tooltip } from "@mantine/core";
import { IconBolt, IconBoltOff, IconPlugConnected, IconPlugConnectedX, IconRefresh } from "@tabler/icons-react";
import { type ReactNode, useState } from "react";
import type { FaultKind, SlaveOut } from "../../api/types";
import { hexH } from "../../lib/hex";
import { notifyError, notifyOk } from "../../lib/notify";
import { connectSlave, injectFault } from "../../store/ethercat";

const FAULT_TITLES: Record<FaultKind, string> = {
  slave_disconnect: "Cable disconnected",
  slave_reconnect: "Cable reconnected",
  drive_fault: "Drive alarm raised",
  drive_fault_clear: "Drive alarm cause cleared",
  main_power_off: "Main power off",
  main_power_on: "Main power on",
  encoder_velocity: "Encoder velocity set",
};

function parseCode(text: string): number | null {
  const t = text.trim().replace(/h$/i, "").replace(/^0x/i, "");
  if (!/^[0-9a-f]{1,4}$/i.test(t)) return null;
  const v = parseInt(t, 16);
  return v >= 1 ? v : null;
}

/** Fault injection for commissioning drills, one click each: the cable, the reconnect command, drive alarms, power. */
export function FaultActions({ slave }: { slave: SlaveOut }) {
  const node = slave.node_address;
  const [busy, setBusy] = useState<string | null>(null);
  const [codeText, setCodeText] = useState("2310");
  const code = parseCode(codeText);

  const run = async (id: string, kind: FaultKind) => {
    setBusy(id);
    try {
      const out = await injectFault(kind, node, code ?? 0x2310);
      const extra = kind === "drive_fault" ? ` (603Fh ${hexH(code ?? 0x2310)})` : "";
      notifyOk(`${FAULT_TITLES[kind]}${extra}`, `${slave.name} (node ${node}) is ${out.slave_state} · cycle ${out.cycle}`);
    } catch (err) {
      notifyError(`${FAULT_TITLES[kind]} on node ${node}`, err);
    } finally {
      setBusy(null);
    }
  };
  const connect = async () => {
    setBusy("connect");
    try {
      const s = await connectSlave(node);
      notifyOk("Reconnect command sent", `${s.name} (node ${node}) is ${s.state}`);
    } catch (err) {
      notifyError(`Connect node ${node}`, err);
    } finally {
      setBusy(null);
    }
  };
  const btn = (id: string, label: string, kind: FaultKind, icon: ReactNode, tip: string, color?: string, off = false) => (
    <Tooltip label={tip} openDelay={400}>
      <Button variant="default" size="compact-xs" leftSection={icon} loading={busy === id}
        disabled={off || (busy !== null && busy !== id)}
        onClick={() => void run(id, kind)} data-testid={`ecat-fault-${id}-${node}`} c={color}>
        {label}
      </Button>
    </Tooltip>
  );
  const servo = slave.kind === "servo";

  return (
    <Group gap={10} wrap="wrap" className="ecat-actions" data-testid={`ecat-actions-${node}`}>
      <Group gap={4} wrap="nowrap">
        <Text size="10px" c="dimmed" tt="uppercase" fw={600}>Cable</Text>
        {btn("disconnect", "Disconnect", "slave_disconnect", <IconPlugConnectedX size={13} />,
          slave.wired ? "Pull the slave's cable: it drops to Init, the axis gets an EtherCAT error" : "The cable is already out",
          slave.wired ? "red.7" : undefined, !slave.wired)}
        {btn("reconnect", "Reconnect", "slave_reconnect", <IconPlugConnected size={13} />,
          slave.wired ? "The cable is plugged in" : "Plug the cable back in (with auto-restart the slave returns to Op)",
          undefined, slave.wired)}
        <Tooltip label="Reconnect command: restart the slave towards Op (it must be on the wire)" openDelay={400}>
          <Button variant="default" size="compact-xs" leftSection={<IconRefresh size={13} />} loading={busy === "connect"}
            disabled={busy !== null && busy !== "connect"} onClick={() => void connect()} data-testid={`ecat-connect-${node}`}>
            Connect
          </Button>
        </Tooltip>
      </Group>
      {servo && (
        <Group gap={4} wrap="nowrap">
          <Text size="10px" c="dimmed" tt="uppercase" fw={600}>Drive</Text>
          <TextInput size="xs" w={72} value={codeText} onChange={(e) => setCodeText(e.currentTarget.value)}
            aria-label="Drive alarm code (603Fh, hex)" data-testid={`ecat-alarm-code-${node}`} error={code === null}
            rightSection={<Text size="xs" c="dimmed">h</Text>} rightSectionWidth={18}
            styles={{ input: { fontFamily: "var(--mantine-font-family-monospace)", height: 22, minHeight: 22 } }} />
          <Tooltip label={code === null ? "Enter the 603Fh code in hex (1–FFFF)" : "Raise a drive alarm with this 603Fh code"}
            openDelay={300}>
            <Button variant="default" size="compact-xs" c="red.7" loading={busy === "alarm"}
              disabled={code === null || (busy !== null && busy !== "alarm")} onClick={() => void run("alarm", "drive_fault")}
              data-testid={`ecat-fault-alarm-${node}`}>
              Drive alarm
            </Button>
          </Tooltip>
          {btn("alarm-clear", "Clear alarm cause", "drive_fault_clear", null,
            "Remove the cause of the drive alarm (then reset the error from the controller)")}
          <Text size="10px" c="dimmed" tt="uppercase" fw={600} ml={6}>Main power</Text>
          {btn("power-off", "Off", "main_power_off", <IconBoltOff size={13} />, "Switch the drive's main circuit off", "red.7")}
          {btn("power-on", "On", "main_power_on", <IconBolt size={13} />, "Switch the drive's main circuit on")}
        </Group>
      )}
    </Group>
  );
}
