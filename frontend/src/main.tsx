import "@mantine/core/styles.css";
import "@mantine/notifications/styles.css";
import "uplot/dist/uPlot.min.css";
import "./styles.css";

import { MantineProvider } from "@mantine/core";
import { Notifications } from "@mantine/notifications";
import { StrictMode } from "react";
import { createRoot } from "react-dom/client";
import { App } from "./App";
import { startAxisConfig } from "./store/axisConfig";
import { startCatalog } from "./store/catalog";
import { startCommands } from "./store/commands";
import { startControl } from "./store/control";
import { startEthercat } from "./store/ethercat";
import { startEvents } from "./store/events";
import { startLive } from "./store/live";
import { theme } from "./theme";

// Module-level services: they live as long as the page (not tied to React mounts).
startControl();
startLive();
startCatalog();
startAxisConfig();
startEvents();
startCommands();
startEthercat();

const root = document.getElementById("root");
if (!root) throw new Error("#root missing from index.html");

createRoot(root).render(
  <StrictMode>
    <MantineProvider theme={theme} defaultColorScheme="light" forceColorScheme="light">
      {/* Bottom left: never over the toolbar or the Stop/Reset buttons of the test-run tab. */}
      <Notifications position="bottom-left" limit={4} zIndex={1000} containerWidth={380} />
      <App />
    </MantineProvider>
  </StrictMode>,
);
