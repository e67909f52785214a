// Shared fixtures of the output tests: small scenes, per-sample reconstruction from progressive
// means, and image statistics.
import { createWavefrontPathTracingComputeRenderer } from '../../src/pathtracer/index.ts';
import type { WavefrontPathTracingOptions, WavefrontPathTracingRenderer } from '../../src/pathtracer/types.ts';
import { createCornellBoxScene } from '../../src/scene/cornell-box.ts';
import type { WavefrontMaterialInput, WavefrontMeshInput } from '../../src/scene/types.ts';
import { testDevice } from '../helpers/gpu.ts';

export const lambert = (color: [number, number, number]): WavefrontMaterialInput => ({ baseColorFactor: [...color, 1], metallicFactor: 0, roughnessFactor: 1, ior: 1 });

/** Orthographic camera whose view is the square [-1, 1]^2 of the z = 0 plane. */
export const squareCamera = { type: 'orthographic' as const, position: [0, 0, 2], target: [0, 0, 0], up: [0, 1, 0], orthographicHeight: 2 };

/** An axis-aligned rectangle in the z = `z` plane facing +z. */
export function rect(x0: number, y0: number, x1: number, y1: number, material: WavefrontMaterialInput | number, z = 0, extra: Partial<WavefrontMeshInput> = {}): WavefrontMeshInput {
  return { positions: [x0, y0, z, x1, y0, z, x1, y1, z, x0, y1, z], indices: [0, 1, 2, 0, 2, 3], material, ...extra };
}

export async function cornellRenderer(size: number, options: Partial<WavefrontPathTracingOptions> = {}): Promise<WavefrontPathTracingRenderer> {
  const scene = createCornellBoxScene();
  return createWavefrontPathTracingComputeRenderer({ device: await testDevice(), width: size, height: size, maxDepth: 6, tileSize: 8, ...scene, ...options });
}

/**
 * Renders `count` frames of one sample and returns every pixel's samples, reconstructed from the
 * progressive means m_k as s_k = k m_k - (k - 1) m_(k-1) (RGB per sample, float64).
 */
/** A converged render of the Cornell box (256 spp, seed 100) as a linear RGBA image: the reference denoisers are compared against. */
export async function convergedCornellReference(size: number): Promise<{ width: number; height: number; data: Float32Array }> {
  const reference = await cornellRenderer(size, { seed: 100, tileSize: 64 });
  try {
    await reference.renderFrame({ samplesPerPixel: 256 });
    return { width: size, height: size, data: (await reference.readRadiance()).data };
  } finally {
    reference.destroy();
  }
}

export async function perSampleRadiance(renderer: WavefrontPathTracingRenderer, count: number): Promise<Float64Array[]> {
  const pixels = renderer.getSnapshot().width * renderer.getSnapshot().height;
  const samples: Float64Array[] = [];
  let previous = new Float64Array(pixels * 3);
  for (let k = 1; k <= count; k++) {
    await renderer.renderFrame({ samplesPerPixel: 1 });
    const mean = (await renderer.readRadiance()).data;
    const s = new Float64Array(pixels * 3);
    const current = new Float64Array(pixels * 3);
    for (let p = 0; p < pixels; p++) {
      for (let c = 0; c < 3; c++) {
        current[3 * p + c] = mean[4 * p + c]!;
        s[3 * p + c] = k * current[3 * p + c]! - (k - 1) * previous[3 * p + c]!;
      }
    }
    samples.push(s);
    previous = current;
  }
  return samples;
}

/** Mean of channel c over the pixels of an RGBA image, optionally inside a rectangle. */
export function meanChannel(data: Float32Array, width: number, c: number, region?: { x: number; y: number; w: number; h: number }): number {
  const height = data.length / 4 / width;
  const r = region ?? { x: 0, y: 0, w: width, h: height };
  let sum = 0;
  for (let y = r.y; y < r.y + r.h; y++) for (let x = r.x; x < r.x + r.w; x++) sum += data[4 * (y * width + x) + c]!;
  return sum / (r.w * r.h);
}

export const luminance = (r: number, g: number, b: number): number => 0.2126 * r + 0.7152 * g + 0.0722 * b;
