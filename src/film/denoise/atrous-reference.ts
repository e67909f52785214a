/**
 * CPU reference of the GPU denoiser (src/film/denoise/atrous-input.wesl and
 * src/film/denoise/atrous.wesl): the same demodulation, variance, edge-stopping weights and a-trous
 * passes, in double precision, for the tests to compare the GPU with, and for offline use on
 * images read back from the renderer (readRadiance and readAov). The emission seen at the first
 * non-specular hit is taken out before filtering and added back after; the filtered reflected
 * radiance is scaled per channel to the raw one's total (energy over the whole image).
 */
import { GpuRendererError } from '../../errors/gpu-renderer-error.ts';
import { requireLinearRgbaImage, type LinearRgbaImage } from '../../io/images/linear-image.ts';

export interface AtrousDenoiseSettings {
  iterations: number;
  sigmaLuminance: number;
  sigmaNormal: number;
  sigmaDepth: number;
}

/** The denoiser's inputs, as readRadiance() and readAov() return them. */
export interface AtrousDenoiseInput {
  /** Mean radiance (rgb). */
  radiance: LinearRgbaImage;
  /** Mean first-hit albedo (rgb); alpha unused. */
  albedo: LinearRgbaImage;
  /** Mean first-hit normal (xyz) with coverage in alpha (the share of samples that hit a surface). */
  normal: LinearRgbaImage;
  /** Mean first-hit depth (r). */
  depth: LinearRgbaImage;
  /** Mean emission seen at the first non-specular hit (rgb): not filtered, added back. */
  emission: LinearRgbaImage;
  /**
   * Variance of every pixel's mean luminance of the radiance without the emission
   * (readAov('variance') alpha); +Infinity: unknown.
   */
  luminanceVariance: Float32Array | Float64Array;
}

/** Below this an albedo channel is not divided out (demodulation), as in the WGSL. */
export const demodulationMinAlbedo = 0.001;
/** Stand-in variance where it is unknown: the luminance edge-stopping then passes everything. */
export const unknownVariance = 1e30;

const luminance = (r: number, g: number, b: number): number => 0.2126 * r + 0.7152 * g + 0.0722 * b;
const b3 = (d: number): number => (d === 0 ? 0.375 : Math.abs(d) === 1 ? 0.25 : 1 / 16);

/** Runs the full filter and returns RGBA (alpha 1), top row first. */
export function denoiseAtrousReference(input: AtrousDenoiseInput, settings: AtrousDenoiseSettings): Float32Array {
  const pixels = requireLinearRgbaImage(input.radiance, 'radiance');
  const { width: w, height: h } = input.radiance;
  for (const key of ['albedo', 'normal', 'depth', 'emission'] as const) {
    requireLinearRgbaImage(input[key], key);
    if (input[key].width !== w || input[key].height !== h) throw new GpuRendererError('INVALID_OPTION', `expected ${w}x${h} like radiance`, { field: key });
  }
  if (input.luminanceVariance.length !== pixels) throw new GpuRendererError('INVALID_OPTION', `expected ${pixels} values`, { field: 'luminanceVariance' });
  const factor = new Float64Array(pixels * 3);
  let color = new Float64Array(pixels * 4);
  const z = new Float64Array(pixels);
  const n = new Float64Array(pixels * 3);
  const hit = new Uint8Array(pixels);
  for (let p = 0; p < pixels; p++) {
    const rad = [0, 1, 2].map((c) => input.radiance.data[4 * p + c]! - input.emission.data[4 * p + c]!);
    for (let c = 0; c < 3; c++) {
      const a = input.albedo.data[4 * p + c]!;
      factor[3 * p + c] = a > demodulationMinAlbedo ? a : 1;
      color[4 * p + c] = rad[c]! / factor[3 * p + c]!;
    }
    const v = input.luminanceVariance[p]!;
    const y = luminance(rad[0]!, rad[1]!, rad[2]!);
    const yi = luminance(color[4 * p]!, color[4 * p + 1]!, color[4 * p + 2]!);
    const scale = y > 0 ? yi / y : 1;
    color[4 * p + 3] = Number.isFinite(v) ? v * scale * scale : unknownVariance;
    z[p] = input.depth.data[4 * p]!;
    const nx = input.normal.data[4 * p]!, ny = input.normal.data[4 * p + 1]!, nz = input.normal.data[4 * p + 2]!;
    const len = Math.hypot(nx, ny, nz);
    n.set(len > 0 ? [nx / len, ny / len, nz / len] : [0, 0, 0], 3 * p);
    hit[p] = input.normal.data[4 * p + 3]! > 0 ? 1 : 0;
  }
  const gradient = new Float64Array(pixels * 2);
  for (let y = 0; y < h; y++) {
    for (let x = 0; x < w; x++) {
      const p = y * w + x;
      const left = x > 0 ? Math.abs(z[p]! - z[p - 1]!) : 1e30;
      const right = x + 1 < w ? Math.abs(z[p + 1]! - z[p]!) : 1e30;
      const up = y > 0 ? Math.abs(z[p]! - z[p - w]!) : 1e30;
      const down = y + 1 < h ? Math.abs(z[p + w]! - z[p]!) : 1e30;
      gradient[2 * p] = w > 1 ? Math.min(left, right) : 0;
      gradient[2 * p + 1] = h > 1 ? Math.min(up, down) : 0;
    }
  }
  for (let i = 0; i < settings.iterations; i++) {
    const step = 1 << i;
    const out = new Float64Array(pixels * 4);
    // 3x3 Gaussian (1/4, 1/2, 1/4) of the variance, renormalised at the border.
    const prefiltered = new Float64Array(pixels);
    for (let y = 0; y < h; y++) {
      for (let x = 0; x < w; x++) {
        let vsum = 0, vweight = 0;
        for (let dy = -1; dy <= 1; dy++) {
          for (let dx = -1; dx <= 1; dx++) {
            const qx = x + dx, qy = y + dy;
            if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
            const k = (dx === 0 ? 0.5 : 0.25) * (dy === 0 ? 0.5 : 0.25);
            vsum += k * color[4 * (qy * w + qx) + 3]!;
            vweight += k;
          }
        }
        prefiltered[y * w + x] = Math.max(vsum / vweight, 0);
      }
    }
    for (let y = 0; y < h; y++) {
      for (let x = 0; x < w; x++) {
        const p = y * w + x;
        const l = luminance(color[4 * p]!, color[4 * p + 1]!, color[4 * p + 2]!);
        let r = 0, g = 0, b = 0, variance = 0, weights = 0;
        for (let dy = -2; dy <= 2; dy++) {
          for (let dx = -2; dx <= 2; dx++) {
            const qx = x + dx * step, qy = y + dy * step;
            if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
            const q = qy * w + qx;
            let wn = !hit[p] && !hit[q] ? 1 : 0;
            if (hit[p] && hit[q]) {
              const d = n[3 * p]! * n[3 * q]! + n[3 * p + 1]! * n[3 * q + 1]! + n[3 * p + 2]! * n[3 * q + 2]!;
              wn = Math.pow(Math.max(0, d), settings.sigmaNormal);
            }
            if (dx === 0 && dy === 0) wn = 1;
            const expected = settings.sigmaDepth * (gradient[2 * p]! * Math.abs(dx * step) + gradient[2 * p + 1]! * Math.abs(dy * step));
            const wz = Math.exp(-Math.abs(z[p]! - z[q]!) / (expected + 1e-4 * Math.abs(z[p]!) + 1e-6));
            const lq = luminance(color[4 * q]!, color[4 * q + 1]!, color[4 * q + 2]!);
            const sigmaL = settings.sigmaLuminance * Math.sqrt(prefiltered[p]! + prefiltered[q]!) + 1e-10;
            const wl = Math.exp(-Math.abs(l - lq) / sigmaL);
            const weight = b3(dx) * b3(dy) * wn * wz * wl;
            r += weight * color[4 * q]!;
            g += weight * color[4 * q + 1]!;
            b += weight * color[4 * q + 2]!;
            variance += weight * weight * color[4 * q + 3]!;
            weights += weight;
          }
        }
        out.set([r / weights, g / weights, b / weights, variance / (weights * weights)], 4 * p);
      }
    }
    color = out;
  }
  // Energy over the whole image: the filtered reflected radiance takes the raw one's total.
  const raw = [0, 0, 0], filtered = [0, 0, 0];
  for (let p = 0; p < pixels; p++) {
    for (let c = 0; c < 3; c++) {
      raw[c]! += input.radiance.data[4 * p + c]! - input.emission.data[4 * p + c]!;
      filtered[c]! += color[4 * p + c]! * factor[3 * p + c]!;
    }
  }
  const scale = [0, 1, 2].map((c) => (filtered[c]! > 0 ? raw[c]! / filtered[c]! : 1));
  const result = new Float32Array(pixels * 4);
  for (let p = 0; p < pixels; p++) {
    for (let c = 0; c < 3; c++) result[4 * p + c] = color[4 * p + c]! * factor[3 * p + c]! * scale[c]! + input.emission.data[4 * p + c]!;
    result[4 * p + 3] = 1;
  }
  return result;
}
