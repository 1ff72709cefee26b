import { useSyncExternalStore } from "react";

/** A tiny external store for `useSyncExternalStore`: immutable state, replaced with `set`. */
export interface Store<T> {
  get(): T;
  set(next: T | ((prev: T) => T)): void;
  subscribe(listener: () => void): () => void;
}

export function createStore<T>(initial: T): Store<T> {
  let state = initial;
  const listeners = new Set<() => void>();
  return {
    get: () => state,
    set(next) {
      const value = typeof next === "function" ? (next as (prev: T) => T)(state) : next;
      if (Object.is(value, state)) return;
      state = value;
      for (const l of [...listeners]) l();
    },
    subscribe(listener) {
      listeners.add(listener);
      return () => listeners.delete(listener);
    },
  };
}

/**
 * Subscribe a component to one slice of a store. The selector must return either a primitive or a reference
 * that already lives in the state (never a freshly built object), so that unchanged slices do not re-render.
 */
export function useStore<T, R>(store: Store<T>, selector: (state: T) => R): R {
  return useSyncExternalStore(
    store.subscribe,
    () => selector(store.get()),
    () => selector(store.get()),
  );
}
