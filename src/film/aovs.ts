/**
 * Arbitrary output variables (AOVs): per-pixel auxiliary images written next to the beauty image,
 * for compositing and as denoiser guides. Each AOV has fixed channel suffixes; in OpenEXR files a
 * channel is named `<aov>.<suffix>` (the OpenEXR layer convention "L.C", which Nuke reads as layer
 * L and Blender as pass L of the unnamed view layer).
 *
 * - albedo, normal, depth: means over the pixel's samples of the first non-specular hit's base
 *   colour, world shading normal and distance from the eye;
 * - emission: the mean emitted radiance reaching the eye from the first non-specular hit (emitters
 *   seen directly or through specular chains; Cycles' Emission pass);
 * - objectId, materialId: the object (instance id) and material (index) of the pixel's first sample
 *   that reached a non-specular surface, -1 where none did;
 * - variance: the variance of the pixel's mean radiance per channel (sample variance / n, the
 *   independent-samples estimate; stratified samples usually do better), and of the mean luminance
 *   of the radiance without the emission (what the denoiser filters);
 * - sampleCount: the samples the pixel received (adaptive sampling gives pixels different counts).
 */
export type WavefrontAovName = 'albedo' | 'normal' | 'depth' | 'emission' | 'objectId' | 'materialId' | 'variance' | 'sampleCount';

/** Channel suffixes per AOV: colours use R,G,B, vectors X,Y,Z, depth Z (Nuke's `depth.Z`), ids `id`. */
export const wavefrontAovChannels: Readonly<Record<WavefrontAovName, readonly string[]>> = Object.freeze({
  albedo: Object.freeze(['R', 'G', 'B']),
  normal: Object.freeze(['X', 'Y', 'Z']),
  depth: Object.freeze(['Z']),
  emission: Object.freeze(['R', 'G', 'B']),
  objectId: Object.freeze(['id']),
  materialId: Object.freeze(['id']),
  variance: Object.freeze(['R', 'G', 'B']),
  sampleCount: Object.freeze(['count']),
});

/** AOVs whose values are integers: files store them as 32-bit floats whatever the pixel type (exact to 2^24). */
export const wavefrontIntegerAovs: readonly WavefrontAovName[] = Object.freeze(['objectId', 'materialId', 'sampleCount'] as WavefrontAovName[]);

export const wavefrontAovNames: readonly WavefrontAovName[] = Object.freeze(['albedo', 'normal', 'depth', 'emission', 'objectId', 'materialId', 'variance', 'sampleCount'] as WavefrontAovName[]);

export function isWavefrontAovName(value: unknown): value is WavefrontAovName {
  return typeof value === 'string' && (wavefrontAovNames as readonly string[]).includes(value);
}
