/**
 * The ground the character walks on: a grid over the route's extent (plus a margin) whose heights
 * are the terrain function's, with normals from central differences, so the drawn ground is the
 * same surface the timeline grounds the character and the props on.
 */
import type { TerrainHeight } from '../../animation/timeline/terrain.ts';
import type { WavefrontMeshInput } from '../../scene/types.ts';

export function groundMesh(terrain: TerrainHeight, min: readonly [number, number], max: readonly [number, number], cells: number): WavefrontMeshInput {
  const positions: number[] = [];
  const normals: number[] = [];
  const uvs: number[] = [];
  const indices: number[] = [];
  const dx = (max[0] - min[0]) / cells;
  const dz = (max[1] - min[1]) / cells;
  const h = 0.5 * Math.min(dx, dz);
  for (let j = 0; j <= cells; j++) {
    for (let i = 0; i <= cells; i++) {
      const x = min[0] + i * dx;
      const z = min[1] + j * dz;
      positions.push(x, terrain(x, z), z);
      const gx = (terrain(x + h, z) - terrain(x - h, z)) / (2 * h);
      const gz = (terrain(x, z + h) - terrain(x, z - h)) / (2 * h);
      const l = Math.hypot(gx, 1, gz);
      normals.push(-gx / l, 1 / l, -gz / l);
      uvs.push(x, z);
    }
  }
  const row = cells + 1;
  for (let j = 0; j < cells; j++) {
    for (let i = 0; i < cells; i++) {
      const a = j * row + i;
      // Counter-clockwise seen from +Y.
      indices.push(a, a + row, a + 1, a + 1, a + row, a + row + 1);
    }
  }
  return { positions, normals, uvs, indices, material: { baseColorFactor: [0.32, 0.42, 0.25, 1], metallicFactor: 0, roughnessFactor: 0.95 } };
}
