/** Poll a request while a view is shown: one request at a time, none while the page is hidden, errors kept as text.
 * Used by the views that read REST resources faster than the WebSocket carries them (3-D robots, process image). */
import { type DependencyList, useEffect, useRef, useState } from "react";

export interface Poll<T> {
  data: T | null;
  error: string | null;
}

export interface PollOptions<T> {
  intervalMs: number;
  /** Poll only while true (e.g. the tab is open). Default true. */
  active?: boolean;
  /** Restart polling (and forget nothing) when one of these changes, e.g. the slave's address. */
  deps?: DependencyList;
  /** Called with every answer, before `data` changes (e.g. to keep the previous answer). */
  onData?: (value: T) => void;
}

export function usePoll<T>(request: () => Promise<T>, options: PollOptions<T>): Poll<T> {
  const { intervalMs, active = true, deps = [], onData } = options;
  const [data, setData] = useState<T | null>(null);
  const [error, setError] = useState<string | null>(null);
  // the latest closures, so that a new render does not restart the interval
  const requestRef = useRef(request);
  const onDataRef = useRef(onData);
  requestRef.current = request;
  onDataRef.current = onData;
  useEffect(() => {
    if (!active) return;
    let alive = true;
    let busy = false;
    const tick = async () => {
      if (busy || document.visibilityState !== "visible") return;
      busy = true;
      try {
        const value = await requestRef.current();
        if (alive) {
          onDataRef.current?.(value);
          setData(value);
          setError(null);
        }
      } catch (err) {
        if (alive) setError(err instanceof Error ? err.message : String(err));
      } finally {
        busy = false;
      }
    };
    void tick();
    const t = setInterval(() => void tick(), intervalMs);
    return () => {
      alive = false;
      clearInterval(t);
    };
  }, [active, intervalMs, ...deps]);
  return { data, error };
}
