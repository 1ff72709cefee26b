import { Anchor, Box, Center, Code, Group, Loader, Stack, Text } from "@mantine/core";
import { IconBox, IconExternalLink } from "@tabler/icons-react";
import { useStore } from "../../store/createStore";
import { vizStore } from "../../store/catalog";
import { RobotPanel } from "./RobotPanel";

/** The 3D view: the viser web app of the backend, in an iframe on its own port, next to the robots' status. */
export function VizView({ active = true }: { active?: boolean }) {
  const { status, data, error } = useStore(vizStore, (s) => s);

  if (status === "loading") {
    return (
      <Center style={{ flex: 1 }}>
        <Loader size="sm" />
      </Center>
    );
  }
  if (status === "error" || !data) {
    return (
      <Center style={{ flex: 1 }}>
        <Text size="sm" c="red">
          Cannot ask the controller about the 3D view: {error}
        </Text>
      </Center>
    );
  }
  if (!data.enabled || !data.port) {
    return (
      <Center style={{ flex: 1 }} data-testid="viser-disabled">
        <Stack align="center" gap={6} maw={460}>
          <IconBox size={36} color="var(--mantine-color-gray-5)" />
          <Text fw={600}>The 3D view is not enabled</Text>
          <Text size="sm" c="dimmed" ta="center">
            Start the backend with a port for the 3D view (viser), for example
          </Text>
          <Code>mcstudio serve --viser-port 8080</Code>
        </Stack>
      </Center>
    );
  }
  const src = `${location.protocol}//${location.hostname}:${data.port}/`;
  return (
    <Stack gap={0} style={{ flex: 1, minHeight: 0 }}>
      <Group gap="xs" px="xs" py={3} justify="flex-end" style={{ borderBottom: "1px solid var(--mantine-color-gray-3)" }}>
        <Anchor href={src} target="_blank" rel="noreferrer" size="xs">
          <Group gap={4} wrap="nowrap">
            Open in a new window <IconExternalLink size={12} />
          </Group>
        </Anchor>
      </Group>
      <Group gap={0} align="stretch" wrap="nowrap" style={{ flex: 1, minHeight: 0 }}>
        <Box style={{ flex: 1, minWidth: 0, minHeight: 0 }}>
          <iframe
            data-testid="viser-frame"
            title="3D view"
            src={src}
            style={{ border: 0, width: "100%", height: "100%", display: "block" }}
          />
        </Box>
        <RobotPanel active={active} />
      </Group>
    </Stack>
  );
}
