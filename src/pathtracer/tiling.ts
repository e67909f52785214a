/**
 * Waves: the unit of wavefront work. A tile wave is one tile of the image (at most tileSize^2
 * paths, the queue capacity) taking one sample number; a list wave (adaptive sampling) takes at most
 * a queue's worth of consecutive entries of the active-pixel list the GPU compacted, each pixel
 * taking its own next sample number. Every path records its own pixel and sample index, so the
 * kernels after the camera never see the difference.
 */
export interface Wave {
  tileOrigin: [number, number];
  /** Tile waves: the tile's size; list waves: (paths, 1). */
  tileSize: [number, number];
  sampleIndex: number;
  /** List waves: first entry of the active-pixel list this wave takes. Absent for tile waves. */
  activeOffset?: number;
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

/**
 * The waves giving one more sample, `samples` times, to each of the `activeCount` pixels of the
 * active list: chunks of at most `capacity` list entries, list-order per sample (a pixel's samples
 * stay in order, so its sample numbers are its film counts).
 */
export function planListWaves(activeCount: number, capacity: number, samples: number): Wave[] {
  const out: Wave[] = [];
  for (let s = 0; s < samples; s++) {
    for (let offset = 0; offset < activeCount; offset += capacity) {
      out.push({ tileOrigin: [0, 0], tileSize: [Math.min(capacity, activeCount - offset), 1], sampleIndex: 0, activeOffset: offset });
    }
  }
  return out;
}

export function tileCount(width: number, height: number, tileSize: number): number {
  return Math.ceil(width / tileSize) * Math.ceil(height / tileSize);
}
