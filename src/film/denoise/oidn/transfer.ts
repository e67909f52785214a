/**
 * Open Image Denoise's HDR input handling (OIDN core/color.h, core/autoexposure.h,
 * devices/gpu/gpu_autoexposure.h), on the CPU: the perceptually uniform (PU) transfer function
 * the `hdr` networks were trained in, normalised so that 65504 maps to 1, and the autoexposure
 * that scales the image so its log-average luminance is 0.18. The WGSL of
 * src/film/denoise/oidn/image.wesl uses the same constants.
 */

/** PU curve coefficients (OIDN TransferFunction::PU), as float32 like OIDN. */
export const pu = {
  a: Math.fround(1.41283765e3),
  b: Math.fround(1.64593172),
  c: Math.fround(4.31384981e-1),
  d: Math.fround(-2.94139609e-3),
  e: Math.fround(1.92653254e-1),
  f: Math.fround(6.26026094e-3),
  g: Math.fround(9.98620152e-1),
  y0: Math.fround(1.5794576e-6),
  y1: Math.fround(3.22087631e-2),
  x0: Math.fround(2.23151711e-3),
  x1: Math.fround(3.70974749e-1),
} as const;

/** Largest HDR value the transfer function maps (half float max). */
export const puYMax = 65504;

export function puForward(y: number): number {
  if (y <= pu.y0) return pu.a * y;
  if (y <= pu.y1) return pu.b * Math.pow(y, pu.c) + pu.d;
  return pu.e * Math.log(y + pu.f) + pu.g;
}

export function puInverse(x: number): number {
  if (x <= pu.x0) return x / pu.a;
  if (x <= pu.x1) return Math.pow((x - pu.d) / pu.b, 1 / pu.c);
  return Math.exp((x - pu.g) / pu.e) - pu.f;
}

/** 1 / forward(65504): the network sees PU values in [0, 1]. */
export const puNormScale = Math.fround(1 / Math.fround(puForward(puYMax)));

/** OIDN's luminance weights (core/color.h). */
export function oidnLuminance(r: number, g: number, b: number): number {
  return 0.212671 * r + 0.71516 * g + 0.072169 * b;
}

/** Autoexposure constants (AutoexposureParams): bins of at most 16x16 pixels, key 0.18. */
export const autoexposureBinSize = 16;
export const autoexposureKey = 0.18;
export const autoexposureEpsilon = 1e-8;

/** Non-finite and negative values read as 0 (OIDN sanitises every input this way). */
export function sanitize(v: number, max = Number.MAX_VALUE): number {
  return Number.isNaN(v) ? 0 : Math.min(Math.max(v, 0), max);
}

/**
 * The input scale OIDN's autoexposure picks for an RGB(A) image (`channels` floats per pixel,
 * top row first): the image is split into ceil(h/16) x ceil(w/16) bins (bin i spans rows
 * [i h / nh, (i + 1) h / nh)); each bin's mean luminance that exceeds 1e-8 enters a log2 average;
 * the scale is 0.18 / 2^average, or 1 when no bin is lit.
 */
export function autoexposure(color: ArrayLike<number>, width: number, height: number, channels = 4): number {
  const binsH = Math.ceil(height / autoexposureBinSize);
  const binsW = Math.ceil(width / autoexposureBinSize);
  let sum = 0;
  let count = 0;
  for (let i = 0; i < binsH; i++) {
    const y0 = Math.floor((i * height) / binsH), y1 = Math.floor(((i + 1) * height) / binsH);
    for (let j = 0; j < binsW; j++) {
      const x0 = Math.floor((j * width) / binsW), x1 = Math.floor(((j + 1) * width) / binsW);
      let l = 0;
      for (let y = y0; y < y1; y++) {
        for (let x = x0; x < x1; x++) {
          const p = channels * (y * width + x);
          l += oidnLuminance(sanitize(color[p]!), sanitize(color[p + 1]!), sanitize(color[p + 2]!));
        }
      }
      const mean = l / ((y1 - y0) * (x1 - x0));
      if (mean > autoexposureEpsilon) {
        sum += Math.log2(mean);
        count++;
      }
    }
  }
  return count > 0 ? autoexposureKey / 2 ** (sum / count) : 1;
}
