/**
 * Arbitrary output variables (AOVs): per-pixel auxiliary images written next to the beauty image,
 * for compositing and as denoiser guides. Each AOV has fixed channel suffixes; in OpenEXR files a
 * channel is named `<aov>.<suffix>` (the OpenEXR layer convention "L.C", which Nuke reads as layer
 * L and Blender as pass L of the unnamed view layer).
 */
export type WavefrontAovName = 'albedo' | 'normal' | 'depth';

/** Channel suffixes per AOV: colours use R,G,B, vectors X,Y,Z, depth Z (Nuke's `depth.Z`). */
export const wavefrontAovChannels: Readonly<Record<WavefrontAovName, readonly string[]>> = Object.freeze({
  albedo: Object.freeze(['R', 'G', 'B']),
  normal: Object.freeze(['X', 'Y', 'Z']),
  depth: Object.freeze(['Z']),
});

export const wavefrontAovNames: readonly WavefrontAovName[] = Object.freeze(['albedo', 'normal', 'depth'] as WavefrontAovName[]);

export function isWavefrontAovName(value: unknown): value is WavefrontAovName {
  return typeof value === 'string' && (wavefrontAovNames as readonly string[]).includes(value);
}
