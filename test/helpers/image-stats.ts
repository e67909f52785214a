/**
 * z-score of the mean per-pixel difference of two RGBA float images, per colour channel: the mean
 * difference over its standard error. Two independent renders of one scene give |z| < 4 unless
 * their expectations differ. Images equal in a channel have no spread: the score is NaN there,
 * which no bound accepts, unless `identicalIsZero` (for renders expected to agree exactly).
 */
export function meanDifferenceZ(a: Float32Array, b: Float32Array, options: { identicalIsZero?: boolean } = {}): number[] {
  const n = a.length / 4;
  return [0, 1, 2].map((c) => {
    let sum = 0, sum2 = 0;
    for (let i = 0; i < n; i++) {
      const d = a[4 * i + c]! - b[4 * i + c]!;
      sum += d;
      sum2 += d * d;
    }
    const mean = sum / n;
    const variance = (sum2 - n * mean * mean) / (n - 1);
    if (options.identicalIsZero && !(variance > 0)) return 0;
    return mean / Math.sqrt(variance / n);
  });
}

/** Relative L1 distance of two images' colour channels (RGBA floats; alpha ignored): sum |a - b| / sum |a|. */
export function relativeL1(a: Float32Array, b: Float32Array): number {
  let sum = 0, diff = 0;
  for (let i = 0; i < a.length; i += 4) {
    for (let c = 0; c < 3; c++) {
      sum += Math.abs(a[i + c]!);
      diff += Math.abs(a[i + c]! - b[i + c]!);
    }
  }
  return diff / sum;
}
