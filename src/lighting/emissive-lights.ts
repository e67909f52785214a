/** Rec. 709 luminance, the same weights as `luminance()` in shaders/lib/color.wesl. */
export function luminance(c: readonly number[]): number {
  return 0.2126 * c[0]! + 0.7152 * c[1]! + 0.0722 * c[2]!;
}

/** An emissive triangle as light builders take it (world space). */
export interface EmissiveTriangleInput {
  /** Triangle slot in the (BVH-ordered) triangle buffers, or any stable id. */
  triangle: number;
  v0: readonly number[];
  v1: readonly number[];
  v2: readonly number[];
  /** Triangle area, as the caller computed it. */
  area: number;
  emission: readonly number[];
  doubleSided: boolean;
}
