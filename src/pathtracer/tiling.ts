/**
 * Waves: the unit of wavefront work. A wave is one tile of the image (at most tileSize^2 paths, the
 * queue capacity) taking one sample number; every path records its own pixel and sample index, so a
 * future schedule (adaptive sampling) can hand pixels different counts without touching the kernels.
 */
export interface Wave {
  tileOrigin: [number, number];
  tileSize: [number, number];
  sampleIndex: number;
}

/** The waves of `samples` samples per pixel starting at sample number `firstSample`, tile-major per sample. */
export function planWaves(width: number, height: number, tileSize: number, firstSample: number, samples: number): Wave[] {
  const out: Wave[] = [];
  for (let s = 0; s < samples; s++) {
    for (let y = 0; y < height; y += tileSize) {
      for (let x = 0; x < width; x += tileSize) {
        out.push({ tileOrigin: [x, y], tileSize: [Math.min(tileSize, width - x), Math.min(tileSize, height - y)], sampleIndex: firstSample + s });
      }
    }
  }
  return out;
}

export function tileCount(width: number, height: number, tileSize: number): number {
  return Math.ceil(width / tileSize) * Math.ceil(height / tileSize);
}
