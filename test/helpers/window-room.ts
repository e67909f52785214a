// A closed 4 x 2.4 x 4 room (y up, floor at y = 0) whose +x wall has a 1.4 x 1 window (y in
// [0.8, 1.8], z in [-0.7, 0.7]): the portal scene of the lighting tests and the lighting bench.
import type { WavefrontMeshInput } from '../../src/scene/types.ts';

type Quad = [number[], number[], number[], number[]];

/** The room's walls as one double-sided grey Lambertian mesh (albedo 0.7). */
export function windowRoomMesh(): WavefrontMeshInput {
  const quads: Quad[] = [
    [[-2, 0, -2], [2, 0, -2], [2, 0, 2], [-2, 0, 2]], // floor
    [[-2, 2.4, -2], [-2, 2.4, 2], [2, 2.4, 2], [2, 2.4, -2]], // ceiling
    [[-2, 0, -2], [-2, 0, 2], [-2, 2.4, 2], [-2, 2.4, -2]], // -x wall
    [[-2, 0, -2], [-2, 2.4, -2], [2, 2.4, -2], [2, 0, -2]], // -z wall
    [[-2, 0, 2], [2, 0, 2], [2, 2.4, 2], [-2, 2.4, 2]], // +z wall
    // +x wall around the window
    [[2, 0, -2], [2, 0.8, -2], [2, 0.8, 2], [2, 0, 2]],
    [[2, 1.8, -2], [2, 2.4, -2], [2, 2.4, 2], [2, 1.8, 2]],
    [[2, 0.8, -2], [2, 1.8, -2], [2, 1.8, -0.7], [2, 0.8, -0.7]],
    [[2, 0.8, 0.7], [2, 1.8, 0.7], [2, 1.8, 2], [2, 0.8, 2]],
  ];
  const positions: number[] = [];
  const indices: number[] = [];
  for (const q of quads) {
    const base = positions.length / 3;
    for (const v of q) positions.push(...v);
    indices.push(base, base + 1, base + 2, base, base + 2, base + 3);
  }
  return { positions, indices, material: { baseColorFactor: [0.7, 0.7, 0.7, 1], metallicFactor: 0, roughnessFactor: 1, ior: 1, doubleSided: true } };
}

/** The window as a portal: cross(edgeU, edgeV) = +x points out of the room. */
export const windowPortal = { center: [2, 1.3, 0], edgeU: [0, 1, 0], edgeV: [0, 0, 1.4] };
