/**
 * The test image of the codec fixtures (fixtures/pattern.*): 32 x 32 RGBA8 with smooth gradients
 * in every channel, so block codecs (ETC1S, UASTC) and AV1 reproduce it within a few levels.
 */
export const patternSize = 32;

export function codecPattern(): Uint8Array {
  const n = patternSize;
  const data = new Uint8Array(n * n * 4);
  for (let y = 0; y < n; y++) {
    for (let x = 0; x < n; x++) {
      const p = (y * n + x) * 4;
      data[p] = Math.round((255 * x) / (n - 1));
      data[p + 1] = Math.round((255 * y) / (n - 1));
      data[p + 2] = Math.round(128 + 100 * Math.sin((2 * Math.PI * (x + y)) / (2 * n)));
      data[p + 3] = Math.round(255 - (160 * y) / (n - 1));
    }
  }
  return data;
}
