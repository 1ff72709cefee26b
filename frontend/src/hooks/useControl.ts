/** Test-run control (store/control.ts): who holds it, and whether this page may only watch. */
import { CLIENT_ID } from "../api/client";
import type { ControlHolder } from "../api/types";
import { controlStore } from "../store/control";
import { useStore } from "../store/createStore";

/** The client holding test-run control (null: nobody, or not known yet). */
export function useControlHolder(): ControlHolder | null {
  return useStore(controlStore, (s) => s.state?.holder ?? null);
}

/** This page holds test-run control. */
export function useHasControl(): boolean {
  return useStore(controlStore, (s) => s.state?.holder?.id === CLIENT_ID);
}

/**
 * Another client holds test-run control: this page may only watch. Test-run controls use it to disable themselves
 * (the server would refuse them with 423 anyway).
 */
export function useReadOnly(): boolean {
  return useStore(controlStore, (s) => {
    const id = s.state?.holder?.id;
    return id !== undefined && id !== CLIENT_ID;
  });
}

/** The name this page shows to the other clients. */
export function useMyName(): string | null {
  return useStore(controlStore, (s) => s.myName);
}

export function useTokenRequired(): boolean {
  return useStore(controlStore, (s) => s.tokenRequired);
}
