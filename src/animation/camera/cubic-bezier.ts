import { fail, requireVec } from '../../errors/validate.ts';

export type CubicBezier = readonly [number, number, number, number];

/** CSS `ease`, the default timing function. */
export const CSS_EASE: CubicBezier = [0.25, 0.1, 0.25, 1];

export function validateCubicBezier(value: unknown, field: string): CubicBezier {
  const [x1, y1, x2, y2] = requireVec(value, 4, field);
  // CSS Easing Functions Level 1, section 2.2: x1 and x2 must be in [0, 1] so x(s) is monotonic.
  if (x1 < 0 || x1 > 1) fail('INVALID_OPTION', `${field}[0]`, `x1 must be in [0, 1], got ${x1}`);
  if (x2 < 0 || x2 > 1) fail('INVALID_OPTION', `${field}[2]`, `x2 must be in [0, 1], got ${x2}`);
  return [x1, y1, x2, y2];
}

/**
 * CSS cubic-bezier(x1, y1, x2, y2) timing function (CSS Easing Functions Level 1, section 2.2):
 * the curve from (0, 0) to (1, 1) with control points (x1, y1), (x2, y2); for input progress x it
 * returns y at the curve parameter s where x(s) = x, found by Newton steps guarded by bisection.
 * Inputs outside [0, 1] are clamped.
 */
export function cubicBezierEasing(curve: CubicBezier): (x: number) => number {
  const [x1, y1, x2, y2] = curve;
  // Bernstein form: B(s) = 3(1-s)^2 s p1 + 3(1-s) s^2 p2 + s^3.
  const bx = (s: number): number => 3 * (1 - s) * (1 - s) * s * x1 + 3 * (1 - s) * s * s * x2 + s * s * s;
  const by = (s: number): number => 3 * (1 - s) * (1 - s) * s * y1 + 3 * (1 - s) * s * s * y2 + s * s * s;
  const dbx = (s: number): number => 3 * (1 - s) * (1 - s) * x1 + 6 * (1 - s) * s * (x2 - x1) + 3 * s * s * (1 - x2);
  return (x: number): number => {
    if (!(x > 0)) return 0;
    if (x >= 1) return 1;
    let lo = 0;
    let hi = 1;
    let s = x;
    for (let i = 0; i < 64; i++) {
      const error = bx(s) - x;
      if (Math.abs(error) < 1e-12) break;
      if (error > 0) hi = s;
      else lo = s;
      const slope = dbx(s);
      const next = slope > 1e-9 ? s - error / slope : (lo + hi) / 2;
      s = next > lo && next < hi ? next : (lo + hi) / 2;
    }
    return by(s);
  };
}
