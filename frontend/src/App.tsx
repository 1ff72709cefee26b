import { AppShell } from "@mantine/core";
import { EventLog } from "./components/events/EventLog";
import { Toolbar } from "./components/toolbar/Toolbar";
import { ProjectTree } from "./components/tree/ProjectTree";
import { Workspace } from "./components/Workspace";
import { useShortcuts } from "./hooks/useShortcuts";

export function App() {
  useShortcuts();
  return (
    <AppShell header={{ height: 48 }} navbar={{ width: 248, breakpoint: 0 }} padding={0}>
      <AppShell.Header>
        <Toolbar />
      </AppShell.Header>
      <AppShell.Navbar>
        <ProjectTree />
      </AppShell.Navbar>
      <AppShell.Main
        style={{ height: "100dvh", display: "flex", flexDirection: "column", background: "var(--mantine-color-gray-1)" }}
      >
        <Workspace />
        <EventLog />
      </AppShell.Main>
    </AppShell>
  );
}
