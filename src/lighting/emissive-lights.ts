/** Rec. 709 luminance, the same weights as `luminance()` in shaders/lib/color.wesl. */
export function luminance(c: readonly number[]): number {
  return 0.2126 * c[0]! + 0.7152 * c[1]! + 0.0722 * c[2]!;
}
