// Procedural RGBA8 images for the built-in scenes (generated, so the demo ships no image files).
import type { WavefrontImageInput } from '@plasius/gpu-renderer';

type Rgb8 = [number, number, number];

/** A checkerboard of `cells` x `cells` squares, `size` pixels square. */
export function checkerImage(size: number, cells: number, a: Rgb8, b: Rgb8): WavefrontImageInput {
  const data = new Uint8Array(size * size * 4);
  const cell = size / cells;
  for (let y = 0; y < size; y++) {
    for (let x = 0; x < size; x++) {
      const c = (Math.floor(x / cell) + Math.floor(y / cell)) % 2 === 0 ? a : b;
      data.set([c[0], c[1], c[2], 255], 4 * (y * size + x));
    }
  }
  return { width: size, height: size, data };
}

/**
 * A glTF metallicRoughness image (G = roughness, B = metalness) of horizontal bands whose
 * roughness steps from `from` to `to`: one object shows the whole roughness range.
 */
export function roughnessBandsImage(size: number, bands: number, from: number, to: number, metallic: number): WavefrontImageInput {
  const data = new Uint8Array(size * size * 4);
  for (let y = 0; y < size; y++) {
    const band = Math.min(bands - 1, Math.floor((y / size) * bands));
    const roughness = from + ((to - from) * band) / Math.max(1, bands - 1);
    for (let x = 0; x < size; x++) data.set([255, Math.round(roughness * 255), Math.round(metallic * 255), 255], 4 * (y * size + x));
  }
  return { width: size, height: size, data };
}
