// A smooth slab in front of an emitter, seen at normal incidence: the geometry and closed form of the
// transmission tests (transmission-render.test.ts, gltf-materials-render.test.ts).
import type { WavefrontMeshInput } from '../../src/scene/types.ts';

/** Axis-aligned box [-h, h]^2 x [z0, z1] with outward counter-clockwise faces. */
export function box(z0: number, z1: number, h = 1): { positions: number[]; indices: number[] } {
  const p = [
    [-h, -h, z0], [h, -h, z0], [h, h, z0], [-h, h, z0],
    [-h, -h, z1], [h, -h, z1], [h, h, z1], [-h, h, z1],
  ];
  const quads = [[4, 5, 6, 7], [1, 0, 3, 2], [0, 4, 7, 3], [5, 1, 2, 6], [3, 7, 6, 2], [0, 1, 5, 4]];
  return { positions: p.flat(), indices: quads.flatMap(([a, b, c, d]) => [a!, b!, c!, a!, c!, d!]) };
}

/** A black, index-matched emitter quad at z = -2 facing +z (emission E). */
export function emitter(e: readonly number[]): WavefrontMeshInput {
  return {
    positions: [-4, -4, -2, 4, -4, -2, 4, 4, -2, -4, 4, -2],
    indices: [0, 1, 2, 0, 2, 3],
    // KHR_materials_emissive_strength carries the HDR part (emissiveFactor stays in [0, 1]).
    material: { baseColorFactor: [0, 0, 0], metallicFactor: 0, roughnessFactor: 1, ior: 1, emissiveFactor: [e[0]! / 4, e[1]! / 4, e[2]! / 4], emissiveStrength: 4 },
  };
}

/** Slab transmittance at normal incidence: interfaces of index n, interior pass transmittance a. */
export function slabTransmittance(n: number, a: number): number {
  const r = ((n - 1) / (n + 1)) ** 2;
  return ((1 - r) ** 2 * a) / (1 - r * r * a * a);
}

