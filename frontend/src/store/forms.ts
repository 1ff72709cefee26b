/**
 * Values typed into the test-run forms, per axis, kept outside the components so that they survive switching tabs
 * (and so that the Esc shortcut can stop with the deceleration of the absolute-move form).
 */
import { createStore, useStore } from "./createStore";

/** Mantine NumberInput values: a number, or the raw text while it is not one yet ("", "-", "1."). */
export type NumValue = number | string;

export interface AxisForms {
  jogVelocity: NumValue;
  jogAcceleration: NumValue;
  absPosition: NumValue;
  absVelocity: NumValue;
  absAcceleration: NumValue;
  absDeceleration: NumValue;
  absJerk: NumValue;
  relDistance: NumValue;
  relVelocity: NumValue;
  relAcceleration: NumValue;
  relDeceleration: NumValue;
  relJerk: NumValue;
  velVelocity: NumValue;
  velAcceleration: NumValue;
  velDeceleration: NumValue;
  velDirection: string;
  /** BufferMode enumerators of the move forms */
  absBufferMode: string;
  relBufferMode: string;
  velBufferMode: string;
  /** Inching: one MC_MoveRelative of ± this distance per press, at the jog velocity and acceleration. */
  inchDistance: NumValue;
  /** MC_SetPosition */
  setPosition: NumValue;
  /** MC_ImmediateStop StopMode: "1", "2" or "3" */
  immediateStopMode: string;
  /** MC_TorqueControl: Torque [%], TorqueRamp [%/s], Velocity (speed limit), Direction */
  trqTorque: NumValue;
  trqRamp: NumValue;
  trqVelocity: NumValue;
  trqDirection: string;
}

export const FORM_DEFAULTS: AxisForms = {
  jogVelocity: 10,
  jogAcceleration: 100,
  absPosition: 0,
  absVelocity: 50,
  absAcceleration: 500,
  absDeceleration: 500,
  absJerk: 0,
  relDistance: 10,
  relVelocity: 50,
  relAcceleration: 500,
  relDeceleration: 500,
  relJerk: 0,
  velVelocity: 20,
  velAcceleration: 500,
  velDeceleration: 500,
  velDirection: "_mcPositiveDirection",
  absBufferMode: "_mcAborting",
  relBufferMode: "_mcAborting",
  velBufferMode: "_mcAborting",
  inchDistance: 1,
  setPosition: 0,
  immediateStopMode: "1",
  trqTorque: 10,
  trqRamp: 100,
  trqVelocity: 20,
  trqDirection: "_mcPositiveDirection",
};

export const formsStore = createStore<Readonly<Record<string, AxisForms>>>({});

export function axisForms(axis: string): AxisForms {
  return formsStore.get()[axis] ?? FORM_DEFAULTS;
}

export function useAxisForms(axis: string): AxisForms {
  return useStore(formsStore, (s) => s[axis] ?? FORM_DEFAULTS);
}

export function setFormField<K extends keyof AxisForms>(axis: string, key: K, value: AxisForms[K]): void {
  formsStore.set((s) => ({ ...s, [axis]: { ...(s[axis] ?? FORM_DEFAULTS), [key]: value } }));
}

/** The number in a form field, or null when the text is not a finite number. */
export function num(v: NumValue): number | null {
  if (typeof v === "number") return Number.isFinite(v) ? v : null;
  const t = v.trim();
  if (t === "") return null;
  const n = Number(t);
  return Number.isFinite(n) ? n : null;
}
