/**
 * Synthetic frames for the denoise-validation tests: a reference with flat areas, hard edges and
 * three detail patches (sheen: fine isotropic texture, chrome: high-contrast checker, wood: fine
 * stripes), and the ways a denoised or raw image can differ from it.
 */
import { rng } from '../helpers/random.ts';
import { gaussianBlur } from '../../src/film/metrics/gaussian-blur.ts';

export const sceneSize = 64;
export const detailRegions = [
  { name: 'sheen', x: 4, y: 40, width: 16, height: 16 },
  { name: 'chrome', x: 24, y: 40, width: 16, height: 16 },
  { name: 'wood', x: 44, y: 40, width: 16, height: 16 },
];

export interface Frame {
  width: number;
  height: number;
  data: Float32Array;
}

/** The grey-level reference luminance at (x, y), written to R = G = B. */
export function referenceValue(x: number, y: number): number {
  let v = 0.4 + 0.3 * (x / sceneSize); // smooth gradient background
  if (x >= 8 && x < 28 && y >= 6 && y < 30) v = 1.2; // a bright box with hard edges
  for (const r of detailRegions) {
    if (x < r.x || x >= r.x + r.width || y < r.y || y >= r.y + r.height) continue;
    if (r.name === 'sheen') v = 0.6 + 0.15 * Math.sin(2.1 * x + 0.3 * y * y) * Math.cos(1.7 * y + 0.2 * x * x);
    if (r.name === 'chrome') v = (x + y) % 2 === 0 ? 1.5 : 0.2;
    if (r.name === 'wood') v = 0.5 + 0.2 * Math.sin(2.4 * x + 0.3 * y);
  }
  return v;
}

export function frame(f: (x: number, y: number) => number): Frame {
  const data = new Float32Array(sceneSize * sceneSize * 4);
  for (let y = 0; y < sceneSize; y++) {
    for (let x = 0; x < sceneSize; x++) {
      const v = f(x, y);
      data.set([v, v, v, 1], 4 * (y * sceneSize + x));
    }
  }
  return { width: sceneSize, height: sceneSize, data };
}

export const reference = (): Frame => frame(referenceValue);

/** Reference plus zero-mean Gaussian noise of relative standard deviation `relative`. */
export function noisy(relative: number, seed: number): Frame {
  const rand = rng(seed);
  const gauss = () => Math.sqrt(-2 * Math.log(1 - rand())) * Math.cos(2 * Math.PI * rand());
  return frame((x, y) => referenceValue(x, y) * (1 + relative * gauss()));
}

/** The reference blurred with a Gaussian of `sigma` pixels (an over-smoothing denoiser). */
export function blurred(sigma: number): Frame {
  const y = new Float64Array(sceneSize * sceneSize);
  for (let j = 0; j < sceneSize; j++) for (let i = 0; i < sceneSize; i++) y[j * sceneSize + i] = referenceValue(i, j);
  const b = gaussianBlur(y, sceneSize, sceneSize, sigma);
  return frame((x, yy) => b[yy * sceneSize + x]);
}

/** Reference with a tile seam: everything right of column 40 in rows 0..31 offset by `step` (relative). */
export function seam(step: number): Frame {
  return frame((x, y) => referenceValue(x, y) * (x >= 40 && y < 32 ? 1 + step : 1));
}

/** Reference with a smooth blotch (Gaussian bump, radius ~3 px) of relative height `height` in a flat area. */
export function blotch(height: number): Frame {
  return frame((x, y) => referenceValue(x, y) * (1 + height * Math.exp(-((x - 50) ** 2 + (y - 15) ** 2) / (2 * 3 * 3))));
}
