import { defineConfig } from "vite";
import react from "@vitejs/plugin-react";

// The backend (mcstudio serve --port 8000) serves the API under /api/v1 and the WebSocket at /api/v1/ws.
// In development Vite proxies both; in production the backend serves dist/ at "/" (same origin).
const backend = process.env.MCSTUDIO_BACKEND ?? "http://127.0.0.1:8000";

export default defineConfig({
  base: "/",
  plugins: [react()],
  server: {
    port: 5173,
    proxy: {
      "/api": { target: backend, changeOrigin: true, ws: true },
      "/docs": { target: backend, changeOrigin: true },
    },
  },
  build: {
    outDir: "dist",
    emptyOutDir: true,
    chunkSizeWarningLimit: 1500,
  },
});
