/** The robots of the 3-D view (GET /api/v1/viz/robots), polled: joint feedback, TCP, alarm, kinematics in force and
 * the user coordinate systems defined with MC_DefineCoordSystem. */
import { useEffect, useState } from "react";
import { api, unwrap } from "../../api/client";
import type { RobotsOut } from "../../api/types";

const POLL_MS = 200;

/** GET /viz/robots every `pollMs` while `active` and the page is visible. */
export function useRobots(active: boolean, pollMs = POLL_MS): { data: RobotsOut | null; error: string | null } {
  const [data, setData] = useState<RobotsOut | null>(null);
  const [error, setError] = useState<string | null>(null);
  useEffect(() => {
    if (!active) return;
    let alive = true;
    let busy = false;
    const tick = async () => {
      if (busy || document.visibilityState !== "visible") return;
      busy = true;
      try {
        const r = await unwrap(api.GET("/api/v1/viz/robots"));
        if (alive) {
          setData(r);
          setError(null);
        }
      } catch (err) {
        if (alive) setError(err instanceof Error ? err.message : String(err));
      } finally {
        busy = false;
      }
    };
    void tick();
    const t = setInterval(() => void tick(), pollMs);
    return () => {
      alive = false;
      clearInterval(t);
    };
  }, [active, pollMs]);
  return { data, error };
}

