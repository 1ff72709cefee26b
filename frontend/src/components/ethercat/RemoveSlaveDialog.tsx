import { Alert, Button, Group, Modal, Stack, Text } from "@mantine/core";
import { IconAlertTriangle, IconTrash } from "@tabler/icons-react";
import { useEffect, useState } from "react";
import { useStore } from "../../store/createStore";
import { useSlave } from "../../store/ethercat";
import { axisOfNode, networkConfigStore, refusalText, refusalTitle } from "../../store/network";
import { type FieldIssue, type Refusal, removeSlave } from "../../store/networkEditor";

/** Confirm removing a slave from the network; a refusal (its axis still uses it, an axis moves) is shown here. */
export function RemoveSlaveDialog({ node, onClose }: { node: number | null; onClose: () => void }) {
  const slave = useSlave(node ?? -1);
  const axes = useStore(networkConfigStore, (s) => s.data?.axes);
  const count = useStore(networkConfigStore, (s) => s.data?.config.slaves.length ?? 0);
  const [busy, setBusy] = useState(false);
  const [issues, setIssues] = useState<FieldIssue[]>([]);
  const [refusal, setRefusal] = useState<Refusal | null>(null);

  useEffect(() => {
    setIssues([]);
    setRefusal(null);
    setBusy(false);
  }, [node]);

  const axis = node !== null && axes ? axisOfNode(axes, node) : undefined;
  const remove = async () => {
    if (node === null) return;
    setBusy(true);
    const res = await removeSlave(node);
    setBusy(false);
    if (res.ok) {
      onClose();
      return;
    }
    setIssues(res.issues);
    setRefusal(res.refusal);
  };

  return (
    <Modal opened={node !== null} onClose={onClose} size="md" centered title={<Text fw={700}>Remove slave?</Text>}
      data-testid="remove-slave-dialog">
      <Stack gap="sm">
        <Text size="sm">
          Remove <b>{slave?.name ?? `node ${node}`}</b> (node {node}{slave ? `, ${slave.device_name}` : ""}) from the
          network? Applying restarts the controller.
        </Text>
        {axis && (
          <Text size="xs" c="orange.8" data-testid="remove-slave-axis">
            {axis.name} uses this slave: the controller refuses to remove it while the axis refers to node {node}.
          </Text>
        )}
        {count === 1 && (
          <Text size="xs" c="dimmed">
            This is the last slave: a project without slaves gets one built-in slave per servo or encoder axis.
          </Text>
        )}
        {(refusal || issues.length > 0) && (
          <Alert color={refusal ? "orange" : "red"} variant="light" py={6} icon={<IconAlertTriangle size={16} />}
            title={refusal ? refusalTitle(refusal.status) : "The controller refused to remove it"}
            data-testid="remove-slave-refusal">
            <Stack gap={2}>
              {refusal && <Text size="xs">{refusalText(refusal.status, refusal.message)}</Text>}
              {issues.map((i, k) => <Text size="xs" key={k}>{i.msg}</Text>)}
            </Stack>
          </Alert>
        )}
        <Group justify="flex-end" gap={8}>
          <Button variant="default" onClick={onClose} data-testid="remove-slave-cancel">Cancel</Button>
          <Button color="red" leftSection={<IconTrash size={14} />} loading={busy} onClick={() => void remove()}
            data-testid="remove-slave-confirm">
            Remove and apply
          </Button>
        </Group>
      </Stack>
    </Modal>
  );
}
