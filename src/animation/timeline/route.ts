import { fail, isArrayLike, requireFiniteNumber, requireVec } from '../../errors/validate.ts';
import type { Vec3 } from '../model/model-types.ts';

export interface RoutePointInput {
  position: readonly number[];
  /** When the character should reach this point, on the scene clock. */
  arriveMs: number;
}

/** A validated route: a polyline on the ground with arrival times and horizontal arc lengths. */
export interface Route {
  readonly points: readonly { readonly position: Readonly<Vec3>; readonly arriveMs: number }[];
  /** Horizontal (xz) distance from the first point to each point. */
  readonly cumulative: Float64Array;
  readonly length: number;
}

/**
 * Validates `route`: at least one point, finite positions, finite arrival times that do not
 * decrease. Distances are horizontal (xz): heights come from the terrain.
 */
export function validateRoute(route: unknown, field = 'route'): Route {
  if (!isArrayLike(route) || route.length === 0) fail('INVALID_OPTION', field, 'expected a non-empty array of route points');
  const points = Array.from(route as ArrayLike<unknown>, (raw, i) => {
    if (typeof raw !== 'object' || raw === null) fail('INVALID_OPTION', `${field}[${i}]`, 'expected { position, arriveMs }');
    const point = raw as RoutePointInput;
    const position = requireVec(point.position, 3, `${field}[${i}].position`) as Vec3;
    const arriveMs = requireFiniteNumber(point.arriveMs, `${field}[${i}].arriveMs`);
    return { position, arriveMs };
  });
  const cumulative = new Float64Array(points.length);
  for (let i = 1; i < points.length; i++) {
    if (points[i].arriveMs < points[i - 1].arriveMs) {
      fail('INVALID_OPTION', `${field}[${i}].arriveMs`, `arrival times must not decrease (${points[i - 1].arriveMs} then ${points[i].arriveMs})`);
    }
    const a = points[i - 1].position;
    const b = points[i].position;
    cumulative[i] = cumulative[i - 1] + Math.hypot(b[0] - a[0], b[2] - a[2]);
  }
  return { points, cumulative, length: cumulative[points.length - 1] };
}

/** Horizontal position and heading (yaw about +Y, 0 facing +Z as glTF models do) at arc length `s`. */
export function routePointAt(route: Route, s: number): { x: number; z: number; yaw: number; segment: number } {
  const n = route.points.length;
  if (n === 1) return { x: route.points[0].position[0], z: route.points[0].position[2], yaw: 0, segment: 0 };
  const clamped = Math.min(Math.max(s, 0), route.length);
  let k = 0;
  while (k < n - 2 && route.cumulative[k + 1] <= clamped) k++;
  // Skip zero-length segments for the heading.
  let h = k;
  while (h < n - 2 && route.cumulative[h + 1] === route.cumulative[h]) h++;
  const a = route.points[k].position;
  const b = route.points[k + 1].position;
  const segmentLength = route.cumulative[k + 1] - route.cumulative[k];
  const u = segmentLength > 0 ? (clamped - route.cumulative[k]) / segmentLength : 0;
  const ha = route.points[h].position;
  const hb = route.points[h + 1].position;
  return { x: a[0] + (b[0] - a[0]) * u, z: a[2] + (b[2] - a[2]) * u, yaw: Math.atan2(hb[0] - ha[0], hb[2] - ha[2]), segment: k };
}

/** Arc length the route schedule reaches at `tMs` (piecewise linear between arrival times, clamped). */
export function routeDistanceAtTime(route: Route, tMs: number): number {
  const points = route.points;
  if (tMs <= points[0].arriveMs) return 0;
  for (let i = 1; i < points.length; i++) {
    if (tMs < points[i].arriveMs) {
      const span = points[i].arriveMs - points[i - 1].arriveMs;
      const u = span > 0 ? (tMs - points[i - 1].arriveMs) / span : 1;
      return route.cumulative[i - 1] + u * (route.cumulative[i] - route.cumulative[i - 1]);
    }
  }
  return route.length;
}
