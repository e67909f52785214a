/** Quaternion helpers on (x, y, z, w) stored at an offset of a numeric array. */

type Numbers = { [index: number]: number; readonly length: number };

export function normaliseQuaternion(q: Numbers, o = 0): void {
  const length = Math.hypot(q[o], q[o + 1], q[o + 2], q[o + 3]);
  if (length === 0) {
    q[o] = 0; q[o + 1] = 0; q[o + 2] = 0; q[o + 3] = 1;
    return;
  }
  q[o] /= length; q[o + 1] /= length; q[o + 2] /= length; q[o + 3] /= length;
}

/**
 * Spherical linear interpolation along the shorter arc, as glTF 2.0 Appendix C writes it:
 * a = acos(|dot|), s = sign(dot), q = sin(a (1 - t)) / sin(a) q0 + s sin(a t) / sin(a) q1, then
 * normalised. Nearly equal rotations fall back to a normalised lerp (sin(a) -> 0).
 */
export function slerpQuaternion(out: Numbers, oo: number, q0: Numbers, o0: number, q1: Numbers, o1: number, t: number): void {
  let dot = q0[o0] * q1[o1] + q0[o0 + 1] * q1[o1 + 1] + q0[o0 + 2] * q1[o1 + 2] + q0[o0 + 3] * q1[o1 + 3];
  const sign = dot < 0 ? -1 : 1;
  dot = Math.min(1, Math.abs(dot));
  let k0: number;
  let k1: number;
  if (dot > 1 - 1e-9) {
    k0 = 1 - t;
    k1 = t;
  } else {
    const angle = Math.acos(dot);
    const sinAngle = Math.sin(angle);
    k0 = Math.sin(angle * (1 - t)) / sinAngle;
    k1 = Math.sin(angle * t) / sinAngle;
  }
  k1 *= sign;
  const x = k0 * q0[o0] + k1 * q1[o1];
  const y = k0 * q0[o0 + 1] + k1 * q1[o1 + 1];
  const z = k0 * q0[o0 + 2] + k1 * q1[o1 + 2];
  const w = k0 * q0[o0 + 3] + k1 * q1[o1 + 3];
  out[oo] = x; out[oo + 1] = y; out[oo + 2] = z; out[oo + 3] = w;
  normaliseQuaternion(out, oo);
}
