import type { AnimationSamplerData } from '../clips/clip-types.ts';
import { normaliseQuaternion, slerpQuaternion } from './quaternion.ts';

type Numbers = { [index: number]: number; readonly length: number };

/** Index k of the last keyframe with input[k] <= t, for input[0] <= t < input[n - 1]. */
function keyframeBefore(input: Float64Array, t: number): number {
  let lo = 0;
  let hi = input.length - 1;
  while (hi - lo > 1) {
    const mid = (lo + hi) >> 1;
    if (input[mid] <= t) lo = mid;
    else hi = mid;
  }
  return lo;
}

function copyValue(sampler: AnimationSamplerData, key: number, out: Numbers, o: number): void {
  const c = sampler.components;
  const element = sampler.interpolation === 'CUBICSPLINE' ? 3 * key + 1 : key;
  for (let i = 0; i < c; i++) out[o + i] = sampler.output[element * c + i];
}

/**
 * Samples a glTF animation sampler at `timeS` seconds into `out[o ..]` (glTF 2.0 section 3.11 and
 * Appendix C):
 * - before the first key and after the last key the first / last value holds (clamping);
 * - STEP holds v_k on [t_k, t_k+1);
 * - LINEAR lerps, or slerps along the shorter arc when `rotation` is set (result normalised);
 * - CUBICSPLINE evaluates the cubic Hermite spline with tangents scaled by the key interval
 *   t_d = t_k+1 - t_k:  p(u) = (2u^3 - 3u^2 + 1) v_k + t_d (u^3 - 2u^2 + u) b_k
 *   + (-2u^3 + 3u^2) v_k+1 + t_d (u^3 - u^2) a_k+1, where b_k is the out-tangent of key k and a_k+1
 *   the in-tangent of key k+1; rotations are normalised afterwards.
 */
export function sampleAnimationSampler(sampler: AnimationSamplerData, timeS: number, rotation: boolean, out: Numbers, o = 0): void {
  const { input, output, components: c } = sampler;
  const last = input.length - 1;
  if (last === 0 || timeS <= input[0]) return copyValue(sampler, 0, out, o);
  if (timeS >= input[last]) return copyValue(sampler, last, out, o);
  const k = keyframeBefore(input, timeS);
  const td = input[k + 1] - input[k];
  const u = (timeS - input[k]) / td;
  switch (sampler.interpolation) {
    case 'STEP':
      return copyValue(sampler, k, out, o);
    case 'LINEAR':
      if (rotation) return slerpQuaternion(out, o, output, k * c, output, (k + 1) * c, u);
      for (let i = 0; i < c; i++) out[o + i] = output[k * c + i] * (1 - u) + output[(k + 1) * c + i] * u;
      return;
    case 'CUBICSPLINE': {
      const u2 = u * u;
      const u3 = u2 * u;
      const h00 = 2 * u3 - 3 * u2 + 1;
      const h10 = (u3 - 2 * u2 + u) * td;
      const h01 = -2 * u3 + 3 * u2;
      const h11 = (u3 - u2) * td;
      const v0 = (3 * k + 1) * c;
      const b0 = (3 * k + 2) * c;
      const a1 = 3 * (k + 1) * c;
      const v1 = (3 * (k + 1) + 1) * c;
      for (let i = 0; i < c; i++) out[o + i] = h00 * output[v0 + i] + h10 * output[b0 + i] + h01 * output[v1 + i] + h11 * output[a1 + i];
      if (rotation) normaliseQuaternion(out, o);
      return;
    }
  }
}
