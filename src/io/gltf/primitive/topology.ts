/**
 * Primitive topologies to triangle lists (glTF 2.0 section 3.7.2.1, "Topology Types"):
 * TRIANGLE_STRIP triangle i is {v_i, v_(i+(1+i%2)), v_(i+(2-i%2))}, which keeps every triangle's
 * winding counter-clockwise; TRIANGLE_FAN triangle i is {v_(i+1), v_(i+2), v_0}. With
 * KHR_mesh_primitive_restart the largest index value of the index type starts a new strip or fan.
 * Triangles that repeat an index (the zero-area stitching triangles of strips) are dropped.
 */

export const MODE_POINTS = 0;
export const MODE_LINES = 1;
export const MODE_LINE_LOOP = 2;
export const MODE_LINE_STRIP = 3;
export const MODE_TRIANGLES = 4;
export const MODE_TRIANGLE_STRIP = 5;
export const MODE_TRIANGLE_FAN = 6;

export const MODE_NAMES: readonly string[] = ['POINTS', 'LINES', 'LINE_LOOP', 'LINE_STRIP', 'TRIANGLES', 'TRIANGLE_STRIP', 'TRIANGLE_FAN'];

export function sequentialIndices(count: number): Uint32Array {
  const out = new Uint32Array(count);
  for (let i = 0; i < count; i++) out[i] = i;
  return out;
}

function splitAtRestart(indices: Uint32Array, restartValue: number | undefined): Uint32Array[] {
  if (restartValue === undefined) return [indices];
  const runs: Uint32Array[] = [];
  let start = 0;
  for (let i = 0; i <= indices.length; i++) {
    if (i === indices.length || indices[i] === restartValue) {
      if (i > start) runs.push(indices.subarray(start, i));
      start = i + 1;
    }
  }
  return runs;
}

function pushTriangle(out: number[], a: number, b: number, c: number): void {
  if (a !== b && b !== c && a !== c) out.push(a, b, c);
}

/**
 * Triangle-list indices for a TRIANGLES, TRIANGLE_STRIP or TRIANGLE_FAN primitive; `indices` are
 * the primitive's indices (or sequential ones). A TRIANGLES list whose length is not a multiple of
 * 3 loses its incomplete last triangle.
 */
export function toTriangleList(mode: number, indices: Uint32Array, restartValue?: number): Uint32Array {
  if (mode === MODE_TRIANGLES) {
    const whole = indices.length - (indices.length % 3);
    return whole === indices.length ? indices : indices.slice(0, whole);
  }
  const out: number[] = [];
  for (const run of splitAtRestart(indices, restartValue)) {
    if (mode === MODE_TRIANGLE_STRIP) {
      for (let i = 0; i + 2 < run.length; i++) {
        if (i % 2 === 0) pushTriangle(out, run[i], run[i + 1], run[i + 2]);
        else pushTriangle(out, run[i], run[i + 2], run[i + 1]);
      }
    } else if (mode === MODE_TRIANGLE_FAN) {
      for (let i = 0; i + 2 < run.length; i++) pushTriangle(out, run[i + 1], run[i + 2], run[0]);
    } else {
      throw new RangeError(`not a triangle mode: ${mode}`);
    }
  }
  return Uint32Array.from(out);
}
