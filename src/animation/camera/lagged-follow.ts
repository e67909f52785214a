import type { Vec3 } from '../model/model-types.ts';

/** Fixed integration step of the follow lag: 240 Hz. */
export const FOLLOW_TICK_MS = 1000 / 240;

/**
 * Exact solution of the first-order lag dx/dt = (d(t) - x) / tau over a step of `dt` when the
 * target moves linearly from d0 to d1: x = d1 - v tau + (x0 - d0 + v tau) e^(-dt / tau), v = (d1 - d0) / dt.
 */
function lagStep(x0: number, d0: number, d1: number, dt: number, tau: number): number {
  const v = (d1 - d0) / dt;
  return d1 - v * tau + (x0 - d0 + v * tau) * Math.exp(-dt / tau);
}

export interface LaggedFollow {
  /** The lagged point at `tMs` for a target path `desiredAt`; starts settled on the target at t = 0. */
  valueAt(tMs: number, desiredAt: (tMs: number) => Vec3): Vec3;
  reset(): void;
}

/**
 * Frame-rate independent follow lag: exponential smoothing with time constant `lagMs` (the camera
 * closes 63% of any gap in lagMs, and trails a target moving at constant velocity v by v * lagMs).
 * The state advances in whole fixed ticks from t = 0, each integrated exactly for a target moving
 * linearly across the tick; the value between ticks is the exact continuation from the last tick.
 * The result is therefore a function of the time alone: any sequence of frame times gives the same
 * camera at the same time. Seeking backwards restarts from t = 0.
 */
export function createLaggedFollow(lagMs: number, tickMs = FOLLOW_TICK_MS): LaggedFollow {
  let ticks = 0;
  let value: Vec3 | null = null;
  let desiredAtTick: Vec3 = [0, 0, 0];
  return {
    reset() {
      ticks = 0;
      value = null;
    },
    valueAt(tMs, desiredAt) {
      const t = Math.max(0, tMs);
      if (!(lagMs > 0)) return desiredAt(t);
      if (value === null || t < ticks * tickMs) {
        ticks = 0;
        desiredAtTick = desiredAt(0);
        value = [...desiredAtTick];
      }
      while ((ticks + 1) * tickMs <= t) {
        const next = desiredAt((ticks + 1) * tickMs);
        value = [0, 1, 2].map((c) => lagStep(value![c], desiredAtTick[c], next[c], tickMs, lagMs)) as Vec3;
        desiredAtTick = next;
        ticks++;
      }
      const dt = t - ticks * tickMs;
      if (dt <= 0) return [...value];
      const now = desiredAt(t);
      return [0, 1, 2].map((c) => lagStep(value![c], desiredAtTick[c], now[c], dt, lagMs)) as Vec3;
    },
  };
}
