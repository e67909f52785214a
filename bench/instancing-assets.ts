/**
 * Deterministic forest .glb files for bench/instancing.ts, built with @gltf-transform/core and
 * EXT_mesh_gpu_instancing (@gltf-transform/extensions):
 *
 * - a terrain: one displaced grid mesh (2 x 128^2 = 32,768 triangles over the forest's square),
 *   placed once;
 * - four tree meshes of about 20k, 40k, 60k and 100k triangles (a trunk and a noisy crown: round,
 *   conical, tall and lumpy), one primitive each with COLOR_0 (bark brown, leaf green) and smooth
 *   normals;
 * - `count` placements in all, one EXT_mesh_gpu_instancing node per tree mesh (TRANSLATION,
 *   ROTATION, SCALE accessors): random tree, position on the terrain, yaw and scale (0.7-1.3, a
 *   little taller or squatter), from a seeded generator, at a fixed density (the square's side
 *   grows with the square root of `count`), so a small forest looks like a patch of the big one.
 *
 * Every value is a function of the arguments, so every run and every machine reads the same bytes.
 */
import { Document, NodeIO, type Buffer as GltfBuffer, type TypedArray } from '@gltf-transform/core';
import { EXTMeshGPUInstancing } from '@gltf-transform/extensions';
import { rng } from '../test/helpers/random.ts';

export interface TreeSpec {
  name: string;
  /** Crown rings and segments: about 2 * rings * segments triangles. */
  rings: number;
  segments: number;
  /** Crown radius as a function of height along it, v in [0, 1] (bottom to top). */
  profile: (v: number) => number;
  crownHeight: number;
  crownBase: number;
  lumps: number;
}

/** About 20k, 40k, 60k and 100k triangles: 2 * rings * segments plus a 24-triangle trunk. */
export const TREES: readonly TreeSpec[] = [
  { name: 'round', rings: 71, segments: 142, profile: (v) => 1.6 * Math.sin(Math.PI * v), crownHeight: 3.2, crownBase: 1.4, lumps: 0.12 },
  { name: 'conifer', rings: 100, segments: 200, profile: (v) => 1.5 * (1 - v) * (0.75 + 0.25 * Math.abs(Math.sin(7 * Math.PI * v))), crownHeight: 6.5, crownBase: 0.8, lumps: 0.05 },
  { name: 'tall', rings: 122, segments: 246, profile: (v) => 1.1 * Math.sin(Math.PI * v) ** 0.8, crownHeight: 5, crownBase: 2.2, lumps: 0.1 },
  { name: 'lumpy', rings: 158, segments: 316, profile: (v) => 2 * Math.sin(Math.PI * v) ** 0.7, crownHeight: 3.6, crownBase: 1.2, lumps: 0.22 },
];

/** Forest density: placements per square unit (10,000 over 400 x 400). */
const DENSITY = 10_000 / (400 * 400);

export function forestSide(count: number): number {
  return Math.sqrt(count / DENSITY);
}

/** Terrain heights: gentle hills (world units). */
export function terrainHeight(x: number, z: number): number {
  return 4 * Math.sin(x * 0.021) * Math.cos(z * 0.017) + 1.5 * Math.sin(x * 0.09 + z * 0.07);
}

interface MeshArrays {
  positions: Float32Array;
  normals: Float32Array;
  colors: Float32Array;
  indices: Uint32Array;
}

/** Smooth vertex normals: area-weighted face normals summed per vertex. */
function vertexNormals(positions: Float32Array, indices: Uint32Array): Float32Array {
  const n = new Float32Array(positions.length);
  for (let t = 0; t < indices.length; t += 3) {
    const a = 3 * indices[t]!, b = 3 * indices[t + 1]!, c = 3 * indices[t + 2]!;
    const e1 = [positions[b]! - positions[a]!, positions[b + 1]! - positions[a + 1]!, positions[b + 2]! - positions[a + 2]!];
    const e2 = [positions[c]! - positions[a]!, positions[c + 1]! - positions[a + 1]!, positions[c + 2]! - positions[a + 2]!];
    const f = [e1[1]! * e2[2]! - e1[2]! * e2[1]!, e1[2]! * e2[0]! - e1[0]! * e2[2]!, e1[0]! * e2[1]! - e1[1]! * e2[0]!];
    for (const v of [a, b, c]) for (let k = 0; k < 3; k++) n[v + k] += f[k]!;
  }
  for (let v = 0; v < n.length; v += 3) {
    const l = Math.hypot(n[v]!, n[v + 1]!, n[v + 2]!) || 1;
    n[v] /= l;
    n[v + 1] /= l;
    n[v + 2] /= l;
  }
  return n;
}

/** A tree in object space, base of the trunk at the origin, y up. */
export function treeMesh(spec: TreeSpec): MeshArrays & { triangles: number } {
  const { rings, segments } = spec;
  const positions: number[] = [];
  const colors: number[] = [];
  const indices: number[] = [];
  // Trunk: an open cylinder of 12 segments (24 triangles) up into the crown.
  const trunkTop = spec.crownBase + 0.3 * spec.crownHeight;
  for (let s = 0; s < 12; s++) {
    const a = (2 * Math.PI * s) / 12;
    for (const [y, r] of [[0, 0.28], [trunkTop, 0.14]] as const) {
      positions.push(r * Math.cos(a), y, r * Math.sin(a));
      colors.push(0.28, 0.18, 0.1);
    }
  }
  for (let s = 0; s < 12; s++) {
    const i = 2 * s, j = 2 * ((s + 1) % 12);
    indices.push(i, i + 1, j, j, i + 1, j + 1);
  }
  // Crown: rings x segments of a surface of revolution with a noisy radius, closed by two poles.
  const base = positions.length / 3;
  const bottom = base;
  positions.push(0, spec.crownBase, 0);
  colors.push(0.12, 0.3, 0.1);
  for (let r = 1; r < rings; r++) {
    const v = r / rings;
    const y = spec.crownBase + v * spec.crownHeight;
    for (let s = 0; s < segments; s++) {
      const a = (2 * Math.PI * s) / segments;
      const lump = 1 + spec.lumps * (Math.sin(5 * a + 9 * v) * Math.sin(13 * v + 3 * a) + 0.5 * Math.sin(23 * a - 17 * v));
      const radius = Math.max(0.02, spec.profile(v) * lump);
      positions.push(radius * Math.cos(a), y, radius * Math.sin(a));
      const g = 0.28 + 0.12 * v + 0.05 * Math.sin(7 * a);
      colors.push(0.1, g, 0.08);
    }
  }
  const top = positions.length / 3;
  positions.push(0, spec.crownBase + spec.crownHeight, 0);
  colors.push(0.14, 0.42, 0.1);
  const ring = (r: number, s: number): number => base + 1 + (r - 1) * segments + (s % segments);
  for (let s = 0; s < segments; s++) indices.push(bottom, ring(1, s + 1), ring(1, s));
  for (let r = 1; r < rings - 1; r++) {
    for (let s = 0; s < segments; s++) {
      const a = ring(r, s), b = ring(r, s + 1), c = ring(r + 1, s), d = ring(r + 1, s + 1);
      indices.push(a, b, c, c, b, d);
    }
  }
  for (let s = 0; s < segments; s++) indices.push(top, ring(rings - 1, s), ring(rings - 1, s + 1));
  const p = Float32Array.from(positions);
  const idx = Uint32Array.from(indices);
  return { positions: p, normals: vertexNormals(p, idx), colors: Float32Array.from(colors), indices: idx, triangles: idx.length / 3 };
}

/** The terrain: a 128 x 128 cell grid over [0, side]^2 (32,768 triangles). */
export function terrainMesh(side: number, cells = 128): MeshArrays & { triangles: number } {
  const positions = new Float32Array((cells + 1) ** 2 * 3);
  const colors = new Float32Array((cells + 1) ** 2 * 3);
  for (let j = 0; j <= cells; j++) {
    for (let i = 0; i <= cells; i++) {
      const x = (i / cells) * side, z = (j / cells) * side;
      const v = j * (cells + 1) + i;
      positions.set([x, terrainHeight(x, z), z], 3 * v);
      colors.set([0.35, 0.3, 0.18], 3 * v);
    }
  }
  const indices = new Uint32Array(cells * cells * 6);
  let o = 0;
  for (let j = 0; j < cells; j++) {
    for (let i = 0; i < cells; i++) {
      const a = j * (cells + 1) + i, b = a + 1, c = a + cells + 1, d = c + 1;
      indices.set([a, c, b, b, c, d], o);
      o += 6;
    }
  }
  return { positions, normals: vertexNormals(positions, indices), colors, indices, triangles: indices.length / 3 };
}

export interface ForestAsset {
  glb: Uint8Array;
  count: number;
  side: number;
  terrainTriangles: number;
  treeTriangles: number[];
  /** Placements of each tree mesh. */
  perTree: number[];
  /** Triangles over every placement (terrain included): what flattening would store. */
  placedTriangles: number;
  /** A camera over the forest's near corner, looking across it low (many trees along each ray). */
  camera: { position: [number, number, number]; target: [number, number, number]; up: [number, number, number]; fovYDegrees: number };
}

/** The forest of `count` tree placements as one .glb (see the file comment). */
export async function forestGlb(count: number, seed = 25): Promise<ForestAsset> {
  const side = forestSide(count);
  const doc = new Document();
  const buffer = doc.createBuffer();
  const accessor = (type: 'SCALAR' | 'VEC3' | 'VEC4', array: Float32Array | Uint32Array) => doc.createAccessor().setType(type).setArray(array as TypedArray).setBuffer(buffer as GltfBuffer);
  const material = doc.createMaterial('vertex colour').setBaseColorFactor([1, 1, 1, 1]).setMetallicFactor(0).setRoughnessFactor(0.9).setDoubleSided(true);
  const meshOf = (name: string, m: MeshArrays) => doc.createMesh(name).addPrimitive(
    doc.createPrimitive()
      .setAttribute('POSITION', accessor('VEC3', m.positions))
      .setAttribute('NORMAL', accessor('VEC3', m.normals))
      .setAttribute('COLOR_0', accessor('VEC3', m.colors))
      .setIndices(accessor('SCALAR', m.indices))
      .setMaterial(material),
  );
  const scene = doc.createScene('forest');
  const terrain = terrainMesh(side);
  scene.addChild(doc.createNode('terrain').setMesh(meshOf('terrain', terrain)));
  const random = rng(seed);
  const placements: { t: number[]; r: number[]; s: number[] }[][] = TREES.map(() => []);
  for (let k = 0; k < count; k++) {
    const tree = Math.floor(random() * TREES.length);
    const x = random() * side, z = random() * side;
    const yaw = random() * 2 * Math.PI;
    const s = 0.7 + 0.6 * random();
    const stretch = 0.85 + 0.3 * random();
    placements[tree]!.push({ t: [x, terrainHeight(x, z) - 0.1, z], r: [0, Math.sin(yaw / 2), 0, Math.cos(yaw / 2)], s: [s, s * stretch, s] });
  }
  const ext = doc.createExtension(EXTMeshGPUInstancing).setRequired(true);
  const treeTriangles: number[] = [];
  TREES.forEach((spec, i) => {
    const mesh = treeMesh(spec);
    treeTriangles.push(mesh.triangles);
    const list = placements[i]!;
    if (list.length === 0) return;
    const batch = ext.createInstancedMesh()
      .setAttribute('TRANSLATION', accessor('VEC3', Float32Array.from(list.flatMap((p) => p.t))))
      .setAttribute('ROTATION', accessor('VEC4', Float32Array.from(list.flatMap((p) => p.r))))
      .setAttribute('SCALE', accessor('VEC3', Float32Array.from(list.flatMap((p) => p.s))));
    scene.addChild(doc.createNode(`${spec.name} trees`).setMesh(meshOf(spec.name, mesh)).setExtension('EXT_mesh_gpu_instancing', batch));
  });
  const glb = await new NodeIO().registerExtensions([EXTMeshGPUInstancing]).writeBinary(doc);
  const perTree = placements.map((p) => p.length);
  const h = terrainHeight(0, 0);
  return {
    glb,
    count,
    side,
    terrainTriangles: terrain.triangles,
    treeTriangles,
    perTree,
    placedTriangles: terrain.triangles + perTree.reduce((sum, n, i) => sum + n * treeTriangles[i]!, 0),
    camera: { position: [0.02 * side, h + 6 + 0.03 * side, 0.02 * side], target: [0.5 * side, h, 0.5 * side], up: [0, 1, 0], fovYDegrees: 50 },
  };
}
