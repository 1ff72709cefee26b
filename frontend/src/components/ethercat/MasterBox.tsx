import { Badge, Group, Text, Tooltip } from "@mantine/core";
import { IconServer2 } from "@tabler/icons-react";
import type { ReactNode } from "react";
import type { EtherCATMaster } from "../../api/types";
import { Led } from "../common/Led";

function Item({ label, children }: { label: string; children: ReactNode }) {
  return (
    <div className="ecat-master-item">
      <Text size="10px" c="dimmed" tt="uppercase" fw={600} style={{ letterSpacing: "0.03em" }}>
        {label}
      </Text>
      <div>{children}</div>
    </div>
  );
}

/** The EtherCAT master: cycle time, distributed clocks, automatic slave restart and how many slaves are in Op. */
export function MasterBox({ master }: { master: EtherCATMaster }) {
  const all = master.slaves_in_op === master.slaves_configured;
  return (
    <div className="ecat-master" data-testid="ecat-master">
      <Group gap={8} wrap="nowrap" className="ecat-master-title">
        <IconServer2 size={18} color="var(--mantine-color-blue-7)" />
        <div>
          <Text size="sm" fw={700} lh={1.2}>
            EtherCAT master
          </Text>
          <Text size="11px" c="dimmed" lh={1.2}>
            {master.explicit ? "Slaves configured in the project" : "One built-in slave per axis (implicit)"}
          </Text>
        </div>
      </Group>
      <Item label="Cycle time">
        <Text size="sm" className="num" data-testid="ecat-cycle-time">
          {master.cycle_time_us} <span className="unit">µs</span>
        </Text>
      </Item>
      <Item label="Distributed clocks">
        <Led
          label={master.settings.dc_enabled ? `On · SYNC0 shift ${master.settings.sync_offset_pct} %` : "Off"}
          on={master.settings.dc_enabled}
          testId="ecat-dc"
        />
      </Item>
      <Item label="Auto-restart slaves">
        <Tooltip label="A slave that comes back after a drop-out returns to Op by itself (else: Connect)" openDelay={300}>
          <div>
            <Led label={master.settings.auto_restart_slaves ? "On" : "Off"} on={master.settings.auto_restart_slaves}
              testId="ecat-auto-restart" />
          </div>
        </Tooltip>
      </Item>
      <Item label="Slaves in Op">
        <Badge size="md" color={all ? "green" : "red"} variant="light" className="num" data-testid="ecat-slaves-in-op"
          style={{ textTransform: "none" }}>
          {master.slaves_in_op} / {master.slaves_configured}
        </Badge>
      </Item>
    </div>
  );
}
