import { Badge, Button, Divider, Group, Popover, Stack, Text, TextInput, Tooltip } from "@mantine/core";
import { IconKey, IconLock, IconLockOpen, IconUserCheck } from "@tabler/icons-react";
import { useState } from "react";
import { useControlHolder, useHasControl, useMyName, useTokenRequired } from "../../hooks/useControl";
import { useStore } from "../../store/createStore";
import { chosenName, controlStore, releaseControl, storeName, takeControl } from "../../store/control";
import { reconnectLive } from "../../store/live";

function Clients() {
  const clients = useStore(controlStore, (s) => s.state?.clients ?? null);
  const connected = clients?.filter((c) => c.connected) ?? [];
  if (connected.length === 0) return null;
  return (
    <Stack gap={2}>
      <Text size="xs" fw={600}>
        Connected ({connected.length})
      </Text>
      {connected.map((c) => (
        <Text size="xs" key={c.id} c="dimmed" truncate="end" data-testid="control-client">
          {c.name}
        </Text>
      ))}
    </Stack>
  );
}

function NameEditor() {
  const myName = useMyName();
  const hasControl = useHasControl();
  const [value, setValue] = useState(chosenName() ?? "");
  const save = () => {
    storeName(value);
    if (hasControl) void takeControl(false); // tells the server the new name at once
    reconnectLive();
  };
  return (
    <Group gap={6} align="flex-end" wrap="nowrap">
      <TextInput size="xs" label="Your name" placeholder={myName ?? "browser"} value={value} maxLength={48}
        onChange={(e) => setValue(e.currentTarget.value)} data-testid="control-name" style={{ flex: 1 }} />
      <Button size="xs" variant="default" onClick={save} data-testid="control-name-save">
        Set
      </Button>
    </Group>
  );
}

/** The toolbar's test-run control: who holds it (everybody sees it), Take / Release, this page's name. */
export function ControlStatus() {
  const holder = useControlHolder();
  const mine = useHasControl();
  const tokenRequired = useTokenRequired();
  const [confirm, setConfirm] = useState(false);

  if (tokenRequired) {
    return (
      <Tooltip multiline w={300} label="This studio is served on a network address: open the address with ?token=… that 'mcstudio serve' printed.">
        <Badge color="red" variant="light" leftSection={<IconKey size={12} />} data-testid="control-status"
          data-state="token" style={{ textTransform: "none" }}>
          Access token needed
        </Badge>
      </Tooltip>
    );
  }
  const state = holder === null ? "free" : mine ? "mine" : "other";
  const label = state === "free" ? "Control free" : state === "mine" ? "You have control" : `Controlled by ${holder!.name}`;
  const color = state === "free" ? "gray" : state === "mine" ? "teal" : "orange";
  const icon = state === "free" ? <IconLockOpen size={12} /> : state === "mine" ? <IconUserCheck size={12} /> : <IconLock size={12} />;

  return (
    <Group gap={4} wrap="nowrap">
      <Popover position="bottom-end" width={280} shadow="md" withArrow>
        <Popover.Target>
          <Badge component="button" color={color} variant="light" leftSection={icon} data-testid="control-status"
            data-state={state} maw={220} style={{ textTransform: "none", cursor: "pointer" }}
            title={holder ? `${holder.name}, since ${new Date(holder.since_s * 1000).toLocaleTimeString()}` : undefined}>
            {label}
          </Badge>
        </Popover.Target>
        <Popover.Dropdown>
          <Stack gap={8}>
            <Text size="xs">
              One browser at a time holds <b>test-run control</b> (moves, jog, servo, mode, stepping, settings that
              restart the controller); the others watch read-only. Your first test-run action takes free control;
              closing the page releases it and stops your jogs.
            </Text>
            <Divider />
            <NameEditor />
            <Clients />
          </Stack>
        </Popover.Dropdown>
      </Popover>
      {state === "mine" && (
        <Button size="compact-xs" variant="default" onClick={() => void releaseControl()} data-testid="control-release">
          Release
        </Button>
      )}
      {state === "free" && (
        <Button size="compact-xs" variant="default" onClick={() => void takeControl(false)} data-testid="control-take">
          Take
        </Button>
      )}
      {state === "other" && (
        <Popover opened={confirm} onChange={setConfirm} position="bottom-end" width={260} shadow="md" withArrow>
          <Popover.Target>
            <Button size="compact-xs" color="orange" variant="light" onClick={() => setConfirm((o) => !o)}
              data-testid="control-take">
              Take
            </Button>
          </Popover.Target>
          <Popover.Dropdown>
            <Stack gap={6}>
              <Text size="xs">
                Take test-run control from <b>{holder!.name}</b>? That page becomes read-only and its jogs stop.
              </Text>
              <Group justify="flex-end" gap={6}>
                <Button size="compact-xs" variant="default" onClick={() => setConfirm(false)}>
                  Cancel
                </Button>
                <Button size="compact-xs" color="orange" data-testid="control-take-confirm"
                  onClick={() => {
                    setConfirm(false);
                    void takeControl(true);
                  }}>
                  Take control
                </Button>
              </Group>
            </Stack>
          </Popover.Dropdown>
        </Popover>
      )}
    </Group>
  );
}
