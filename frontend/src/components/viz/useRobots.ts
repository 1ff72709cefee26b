/** The robots of the 3-D view (GET /api/v1/viz/robots), polled: joint feedback, TCP, alarm, kinematics in force and
 * the user coordinate systems defined with MC_DefineCoordSystem. */
import { api, unwrap } from "../../api/client";
import type { RobotsOut } from "../../api/types";
import { type Poll, usePoll } from "../../lib/usePoll";

const POLL_MS = 200;

/** GET /viz/robots every `pollMs` while `active` and the page is visible. */
export function useRobots(active: boolean, pollMs = POLL_MS): Poll<RobotsOut> {
  return usePoll(() => unwrap(api.GET("/api/v1/viz/robots")), { intervalMs: pollMs, active });
}
