import type { Pose } from './pose.ts';

export interface PoseLayer {
  readonly pose: Pose;
  readonly weight: number;
}

/**
 * Cross-fades poses by normalised weights. Translations, scales and morph weights blend linearly
 * per component. Rotations blend by weighted nlerp: each quaternion is flipped into the hemisphere
 * of the first layer's (shortest path), summed with its weight and normalised. nlerp rather than
 * slerp because it is order-independent for any number of layers (slerp is defined for two) and,
 * for the small angles between poses of a cross-fade, differs from slerp only in the rate along
 * the same arc (the result stays on the great circle between the two rotations).
 */
export function blendPoses(layers: readonly PoseLayer[], out: Pose): Pose {
  let total = 0;
  for (const layer of layers) if (layer.weight > 0) total += layer.weight;
  if (!(total > 0)) throw new RangeError('blendPoses needs at least one layer with a positive weight');
  out.translations.fill(0);
  out.rotations.fill(0);
  out.scales.fill(0);
  for (const w of out.weights) w.fill(0);
  const reference = layers.find((layer) => layer.weight > 0)!.pose.rotations;
  for (const layer of layers) {
    if (!(layer.weight > 0)) continue;
    const k = layer.weight / total;
    const { translations, rotations, scales, weights } = layer.pose;
    for (let i = 0; i < translations.length; i++) out.translations[i] += k * translations[i];
    for (let i = 0; i < scales.length; i++) out.scales[i] += k * scales[i];
    for (let o = 0; o < rotations.length; o += 4) {
      const dot = rotations[o] * reference[o] + rotations[o + 1] * reference[o + 1] + rotations[o + 2] * reference[o + 2] + rotations[o + 3] * reference[o + 3];
      const s = dot < 0 ? -k : k;
      for (let c = 0; c < 4; c++) out.rotations[o + c] += s * rotations[o + c];
    }
    weights.forEach((w, n) => {
      for (let i = 0; i < w.length; i++) out.weights[n][i] += k * w[i];
    });
  }
  for (let o = 0; o < out.rotations.length; o += 4) {
    const length = Math.hypot(out.rotations[o], out.rotations[o + 1], out.rotations[o + 2], out.rotations[o + 3]);
    for (let c = 0; c < 4; c++) out.rotations[o + c] /= length;
  }
  return out;
}
