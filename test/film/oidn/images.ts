// Synthetic inputs for the OIDN tests: a noisy HDR image with hard albedo and normal edges, bright
// outliers (fireflies up to 200x), a dark corner and an emitter, so the transfer function, the
// padding, the emission bypass and every channel matter.
import { rng } from '../../helpers/random.ts';

export interface TestImages {
  width: number;
  height: number;
  color: Float32Array;
  albedo: Float32Array;
  normal: Float32Array;
  /** Exact emission inside the colour (a bright square), for the emission bypass. */
  emission: Float32Array;
}

export function testImages(width: number, height: number, seed = 1): TestImages {
  const rand = rng(seed);
  const color = new Float32Array(width * height * 4);
  const albedo = new Float32Array(width * height * 4);
  const normal = new Float32Array(width * height * 4);
  const emission = new Float32Array(width * height * 4);
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      const p = 4 * (y * width + x);
      const left = x < width / 2;
      const light = x + y < 6 ? 0 : left ? 0.4 : 3;
      for (let c = 0; c < 3; c++) {
        const a = left ? 0.8 - 0.2 * c : 0.2 + 0.25 * c;
        albedo[p + c] = a;
        color[p + c] = light * a * (rand() < 0.05 ? 200 * rand() : 2 * rand());
      }
      const tilt = y < height / 2 ? 0 : 0.7;
      normal.set([tilt, 1, -tilt, 0], p);
      if (x >= width / 4 && x < width / 2 && y >= height / 4 && y < height / 2) {
        for (let c = 0; c < 3; c++) {
          emission[p + c] = 20 + 5 * c;
          color[p + c]! += emission[p + c]!;
        }
      }
      color[p + 3] = 1;
      albedo[p + 3] = 1;
    }
  }
  return { width, height, color, albedo, normal, emission };
}
