/**
 * Waves: the unit of wavefront work. A frame's work is the linear range pixels x samples (sample
 * by sample, pixels in row-major order); a full-frame wave takes a contiguous run of at most
 * `capacity` paths of it, so a small image takes several samples per pixel in one wave and a large
 * one a band of rows. A list wave (adaptive sampling) takes a run of the step's range of
 * active-list entries x passes the same way, over the list the GPU compacted. Every path records
 * its own pixel and sample index, so the kernels after the camera never see the difference
 * (wave-paths.wesl maps slots to pixels and samples).
 */
export interface Wave {
  /** Full-frame waves: pixel of the first path (below the image's pixels); list waves: offset into the step's range. */
  firstPath: number;
  /** Full-frame waves: sample number of the first path. */
  firstSample: number;
  /** Paths in the wave (list waves: an upper bound; the GPU's list length bounds them). */
  pathCount: number;
  /** List waves: samples each active pixel takes in the step; 0 for full-frame waves. */
  passes: number;
  list: boolean;
}

/** The waves of `samples` samples of each of `pixels` pixels, starting at sample number `firstSample`. */
export function planFrameWaves(pixels: number, capacity: number, firstSample: number, samples: number): Wave[] {
  const out: Wave[] = [];
  const total = pixels * samples;
  for (let start = 0; start < total; start += capacity) {
    out.push({ firstPath: start % pixels, firstSample: firstSample + Math.floor(start / pixels), pathCount: Math.min(capacity, total - start), passes: 0, list: false });
  }
  return out;
}

/**
 * The waves giving `passes` more samples to each of the `activeCount` pixels of the active list:
 * runs of at most `capacity` entries of the range entries x passes (a pixel's samples stay in
 * order, so its sample numbers are its film counts).
 */
export function planListWaves(activeCount: number, capacity: number, passes: number): Wave[] {
  const out: Wave[] = [];
  const total = activeCount * passes;
  for (let start = 0; start < total; start += capacity) {
    out.push({ firstPath: start, firstSample: 0, pathCount: Math.min(capacity, total - start), passes, list: true });
  }
  return out;
}
