// Scenes for the two-level acceleration tests: meshes placed many times under every kind of
// transform, built with the scene API (what an InstancedMesh or BatchedMesh maps to).
import type { WavefrontInstanceInput, WavefrontMaterialInput, WavefrontMeshInput } from '../../src/scene/types.ts';
import { icosphere } from '../helpers/meshes.ts';

export type Mat4 = number[];

/** Column-major 4x4 of translation * rotation (about a unit axis) * scale: glTF's TRS. */
export function trs(t: readonly number[], axis: readonly number[], angle: number, s: readonly number[]): Mat4 {
  const [x, y, z] = axis as [number, number, number];
  const c = Math.cos(angle), n = Math.sin(angle), k = 1 - c;
  const r = [
    [c + x * x * k, x * y * k - z * n, x * z * k + y * n],
    [y * x * k + z * n, c + y * y * k, y * z * k - x * n],
    [z * x * k - y * n, z * y * k + x * n, c + z * z * k],
  ];
  const m = new Array<number>(16).fill(0);
  for (let col = 0; col < 3; col++) for (let row = 0; row < 3; row++) m[4 * col + row] = r[row]![col]! * s[col]!;
  m[12] = t[0]!;
  m[13] = t[1]!;
  m[14] = t[2]!;
  m[15] = 1;
  return m;
}

/** A closed wedge (triangular prism with a slanted top): asymmetric, so a mirror changes what is seen. */
export function wedge(): { positions: number[]; indices: number[] } {
  const positions = [
    0, 0, 0, 1, 0, 0, 0, 0.8, 0, // front face (z = 0): right triangle with the right angle at the origin
    0, 0, 0.5, 1, 0, 0.5, 0, 0.8, 0.5, // back face (z = 0.5)
  ].map((v) => v - 0.3);
  // Counter-clockwise seen from outside.
  const indices = [0, 2, 1, 3, 4, 5, 0, 1, 4, 0, 4, 3, 0, 3, 5, 0, 5, 2, 1, 2, 5, 1, 5, 4];
  return { positions, indices };
}

function smoothSphere(subdivisions: number): { positions: number[]; indices: number[]; normals: number[] } {
  const s = icosphere(0.35, [0, 0, 0], subdivisions);
  return { ...s, normals: s.positions.map((v) => v / 0.35) };
}

/**
 * A ground plane placed once, a smooth sphere placed four times (rotated, non-uniformly scaled,
 * mirrored), a single-sided wedge placed three times (one mirrored), an alpha-masked card twice
 * (with a material override on one) and an emissive panel twice: each placement its own light.
 */
export function transformsScene(): { meshes: WavefrontMeshInput[]; instances: WavefrontInstanceInput[]; materials: WavefrontMaterialInput[] } {
  const ground: WavefrontMeshInput = { positions: [-3, 0, -3, 3, 0, -3, 3, 0, 3, -3, 0, 3], indices: [0, 2, 1, 0, 3, 2], material: { baseColorFactor: [0.6, 0.6, 0.6], metallicFactor: 0, roughnessFactor: 1 } };
  const sphere: WavefrontMeshInput = { ...smoothSphere(2), material: { baseColorFactor: [0.8, 0.3, 0.2], metallicFactor: 0, roughnessFactor: 0.6 } };
  const prism: WavefrontMeshInput = { ...wedge(), material: { baseColorFactor: [0.2, 0.6, 0.3], metallicFactor: 0, roughnessFactor: 0.8, doubleSided: false } };
  // Vertex alphas 0 and 1 across the card: MASK at 0.5 cuts it along a diagonal band.
  const card: WavefrontMeshInput = {
    positions: [-0.4, 0, 0, 0.4, 0, 0, 0.4, 0.8, 0, -0.4, 0.8, 0],
    indices: [0, 1, 2, 0, 2, 3],
    colors: [1, 1, 1, 0, 1, 1, 1, 1, 1, 1, 1, 0, 1, 1, 1, 1],
    material: { baseColorFactor: [0.3, 0.4, 0.9], metallicFactor: 0, roughnessFactor: 1, alphaMode: 'MASK', alphaCutoff: 0.5, doubleSided: true },
  };
  const panel: WavefrontMeshInput = { positions: [-0.3, 0, -0.3, 0.3, 0, -0.3, 0.3, 0, 0.3, -0.3, 0, 0.3], indices: [0, 1, 2, 0, 2, 3], material: { baseColorFactor: [0, 0, 0], emissiveFactor: [1, 0.9, 0.7], emissiveStrength: 6 } };
  const y = [0, 1, 0];
  const instances: WavefrontInstanceInput[] = [
    { mesh: 0 },
    { mesh: 1, transform: trs([-1.2, 0.35, 0], y, 0, [1, 1, 1]) },
    { mesh: 1, transform: trs([-0.2, 0.3, 0.6], [1 / Math.SQRT2, 0, 1 / Math.SQRT2], 0.7, [1.6, 0.85, 0.7]) },
    { mesh: 1, transform: trs([0.9, 0.4, -0.4], y, 0.4, [-1.1, 1.15, 0.9]) },
    { mesh: 1, transform: trs([1.5, 0.25, 0.7], [0, 0, 1], 0.3, [0.7, 0.7, -1.4]) },
    { mesh: 2, transform: trs([-0.8, 0.3, -0.9], y, 0.5, [1, 1, 1]) },
    { mesh: 2, transform: trs([0.3, 0.3, -1.1], y, -0.6, [-1, 1, 1]) },
    { mesh: 2, transform: trs([0.2, 0.3, 1.3], [1, 0, 0], 0.4, [1.3, 0.6, 1.8]) },
    { mesh: 3, transform: trs([-0.6, 0, 1.1], y, 0.3, [1, 1, 1]) },
    { mesh: 3, transform: trs([1.1, 0, 1.4], y, -0.9, [1.5, 0.8, 1]), material: 0 },
    { mesh: 4, transform: trs([-0.8, 2.2, 0.3], [1, 0, 0], Math.PI, [1, 1, 1]) },
    { mesh: 4, transform: trs([0.9, 2.0, -0.2], [1, 0, 0], Math.PI - 0.3, [1.4, 1, 0.8]) },
  ];
  const materials: WavefrontMaterialInput[] = [{ baseColorFactor: [0.9, 0.8, 0.2], metallicFactor: 0, roughnessFactor: 1, alphaMode: 'MASK', alphaCutoff: 0.5, doubleSided: true }];
  return { meshes: [ground, sphere, prism, card, panel], instances, materials };
}

export const transformsCamera = { position: [0, 2.6, 4.2], target: [0, 0.35, 0], up: [0, 1, 0], fovYDegrees: 45 } as const;
