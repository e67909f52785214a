/**
 * The sRGB transfer functions (IEC 61966-2-1:1999), scalar: the CPU side of
 * src/shaders/lib/color.wesl. Texture decoding, display encoding and the tests all use these.
 */

/** Exact sRGB encoding (IEC 61966-2-1:1999), scalar. */
export function linearToSrgb(x: number): number {
  return x <= 0.0031308 ? x * 12.92 : 1.055 * Math.pow(x, 1 / 2.4) - 0.055;
}

/** Exact sRGB decoding (IEC 61966-2-1:1999), scalar; the inverse of linearToSrgb. */
export function srgbToLinear(x: number): number {
  return x <= 0.04045 ? x / 12.92 : Math.pow((x + 0.055) / 1.055, 2.4);
}
