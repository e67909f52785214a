// Deterministic meshes and rays shared by the BVH tests (9 floats per triangle: v0, v1, v2).
import { rng } from '../helpers/random.ts';

export { rng };


/** Random triangles of random size scattered in a cube of side `extent`. */
export function randomSoup(count: number, seed: number, extent = 10, size = 1): Float32Array {
  const r = rng(seed);
  const p = new Float32Array(count * 9);
  for (let i = 0; i < count; i++) {
    const cx = r() * extent, cy = r() * extent, cz = r() * extent;
    const s = size * (0.05 + r());
    for (let v = 0; v < 3; v++) {
      p[i * 9 + v * 3] = cx + (r() - 0.5) * s;
      p[i * 9 + v * 3 + 1] = cy + (r() - 0.5) * s;
      p[i * 9 + v * 3 + 2] = cz + (r() - 0.5) * s;
    }
  }
  return p;
}

/** An n x n grid of quads (2 triangles each) over [0, n]^2, displaced in z (flat when amplitude = 0). */
export function gridMesh(n: number, amplitude = 0.5): Float32Array {
  const p = new Float32Array(n * n * 18);
  const h = (x: number, y: number): number => amplitude * Math.sin(x * 0.7) * Math.cos(y * 0.45);
  let o = 0;
  const put = (x: number, y: number): void => {
    p[o++] = x;
    p[o++] = y;
    p[o++] = h(x, y);
  };
  for (let j = 0; j < n; j++) {
    for (let i = 0; i < n; i++) {
      put(i, j); put(i + 1, j); put(i + 1, j + 1);
      put(i, j); put(i + 1, j + 1); put(i, j + 1);
    }
  }
  return p;
}

/** A soup where a third of the triangles are degenerate: collinear vertices or a single point. */
export function soupWithZeroArea(count: number, seed: number): Float32Array {
  const p = randomSoup(count, seed);
  const r = rng(seed + 99);
  for (let i = 0; i < count; i++) {
    const kind = Math.floor(r() * 3);
    if (kind === 0) {
      // v2 on the segment v0-v1
      const a = r();
      for (let c = 0; c < 3; c++) p[i * 9 + 6 + c] = p[i * 9 + c]! + a * (p[i * 9 + 3 + c]! - p[i * 9 + c]!);
    } else if (kind === 1) {
      for (let c = 0; c < 3; c++) p[i * 9 + 3 + c] = p[i * 9 + 6 + c] = p[i * 9 + c]!;
    }
  }
  return p;
}

/** `count` copies of one triangle: every centroid coincides, every hit is a tie. */
export function identicalTriangles(count: number): Float32Array {
  const p = new Float32Array(count * 9);
  const tri = [0, 0, 0, 1, 0, 0.2, 0.3, 1, -0.1];
  for (let i = 0; i < count; i++) p.set(tri, i * 9);
  return p;
}

/** A soup whose triangles each appear `copies` times, shuffled. */
export function duplicatedSoup(unique: number, copies: number, seed: number): Float32Array {
  const base = randomSoup(unique, seed);
  const r = rng(seed + 7);
  const ids = Array.from({ length: unique * copies }, (_, i) => i % unique);
  for (let i = ids.length - 1; i > 0; i--) {
    const j = Math.floor(r() * (i + 1));
    [ids[i], ids[j]] = [ids[j]!, ids[i]!];
  }
  const p = new Float32Array(ids.length * 9);
  ids.forEach((id, i) => p.set(base.subarray(id * 9, id * 9 + 9), i * 9));
  return p;
}

/** Small triangles at exponentially growing distances (1.5^i): SAH peels one off per level. */
export function exponentialSpacing(count: number): Float32Array {
  const p = new Float32Array(count * 9);
  for (let i = 0; i < count; i++) {
    const x = 1.5 ** (i % 200) * (1 + Math.floor(i / 200) * 1e-3);
    p.set([x, 0, 0, x * 1.0001, 1e-3 * x, 0, x, 0, 1e-3 * x], i * 9);
  }
  return p;
}

/** Two clusters twenty orders of magnitude apart. */
export function hugeRangeSoup(count: number, seed: number): Float32Array {
  const near = randomSoup(count >> 1, seed, 1, 0.1);
  const far = randomSoup(count - (count >> 1), seed + 1, 1e20, 1e19);
  const p = new Float32Array(count * 9);
  p.set(near, 0);
  p.set(far, near.length);
  return p;
}

export interface TestRay {
  origin: Float32Array;
  direction: Float32Array;
}

/**
 * Rays with f32 components (what a GPU sees): half aimed at a random interior point of a random
 * triangle (so most of them hit), a quarter in random directions, a quarter axis-aligned (zero
 * direction components exercise the slab test's safe inverse).
 */
export function makeRays(positions: Float32Array, count: number, seed: number): TestRay[] {
  const r = rng(seed);
  const n = positions.length / 9;
  const lo = [Infinity, Infinity, Infinity];
  const hi = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < positions.length; i += 3) {
    for (let c = 0; c < 3; c++) {
      lo[c] = Math.min(lo[c]!, positions[i + c]!);
      hi[c] = Math.max(hi[c]!, positions[i + c]!);
    }
  }
  const span = Math.max(hi[0]! - lo[0]!, hi[1]! - lo[1]!, hi[2]! - lo[2]!, 1e-3);
  const rays: TestRay[] = [];
  for (let k = 0; k < count; k++) {
    const origin = new Float32Array(3);
    for (let c = 0; c < 3; c++) origin[c] = lo[c]! - 0.2 * span + r() * ((hi[c]! - lo[c]!) + 0.4 * span);
    const d = [0, 0, 0];
    const mode = k % 4;
    if (mode < 2 && n > 0) {
      const t = Math.floor(r() * n);
      let a = r(), b = r();
      if (a + b > 1) { a = 1 - a; b = 1 - b; }
      for (let c = 0; c < 3; c++) {
        const v0 = positions[t * 9 + c]!;
        d[c] = v0 + a * (positions[t * 9 + 3 + c]! - v0) + b * (positions[t * 9 + 6 + c]! - v0) - origin[c]!;
      }
    } else if (mode === 2) {
      const z = 2 * r() - 1, phi = 2 * Math.PI * r(), s = Math.sqrt(1 - z * z);
      d[0] = s * Math.cos(phi); d[1] = s * Math.sin(phi); d[2] = z;
    } else {
      d[Math.floor(r() * 3)] = r() < 0.5 ? -1 : 1;
    }
    const len = Math.hypot(d[0]!, d[1]!, d[2]!) || 1;
    rays.push({ origin, direction: Float32Array.from(d, (x) => x / len) });
  }
  return rays;
}
