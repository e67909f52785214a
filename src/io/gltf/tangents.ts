/**
 * MikkTSpace tangents (Mikkelsen 2008, "Simulation of Wrinkled Surfaces Revisited"; the tangent
 * space glTF 2.0 section 3.7.2.1 prescribes when TANGENT is absent), computed with the `mikktspace`
 * WebAssembly port as @gltf-transform's `tangents()` does: the mesh is unwelded to one vertex per
 * triangle corner, tangents are generated, and identical corners are welded back together.
 *
 * Handedness: MikkTSpace's bitangent follows increasing v (a bottom-left texture origin), while
 * glTF's texture coordinates start at the image's top left (glTF 2.0 section 3.8.3) and its
 * normal textures' +Y is up (material.schema.json, normalTexture), so glTF's bitangent cross(N, T) w follows decreasing v:
 * every generated w is negated, as the mikktspace package prescribes for glTF and three.js's
 * computeMikkTSpaceTangents does. Authored TANGENTs (Blender's glTF exporter) agree.
 */
import type { VertexStreams } from './vertex-streams.ts';

type GenerateTangents = (position: Float32Array, normal: Float32Array, texcoord: Float32Array) => Float32Array;
let generator: Promise<GenerateTangents> | undefined;

/**
 * `mikktspace` as this module imports it. The npm package's builds are ready once imported; the
 * package's browser build (dist/browser, scripts/browser-build) substitutes a module that runs the
 * same WebAssembly from inlined bytes, which it compiles asynchronously in `ready()`.
 */
interface MikkTSpaceModule {
  generateTangents: GenerateTangents;
  ready?: () => Promise<void>;
}

async function loadGenerator(): Promise<GenerateTangents> {
  const module: MikkTSpaceModule = await import('mikktspace');
  await module.ready?.();
  return module.generateTangents;
}

function unweld(values: Float32Array, size: number, indices: Uint32Array): Float32Array {
  const out = new Float32Array(indices.length * size);
  for (let c = 0; c < indices.length; c++) {
    for (let k = 0; k < size; k++) out[c * size + k] = values[indices[c] * size + k];
  }
  return out;
}

/** Per-corner face normals (counter-clockwise front faces), for meshes without NORMAL. */
function flatNormals(cornerPositions: Float32Array): Float32Array {
  const out = new Float32Array(cornerPositions.length);
  for (let t = 0; t < cornerPositions.length; t += 9) {
    const p = cornerPositions;
    const e1 = [p[t + 3] - p[t], p[t + 4] - p[t + 1], p[t + 5] - p[t + 2]];
    const e2 = [p[t + 6] - p[t], p[t + 7] - p[t + 1], p[t + 8] - p[t + 2]];
    let n = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]];
    const len = Math.hypot(n[0], n[1], n[2]);
    n = len > 0 ? n.map((x) => x / len) : [0, 0, 1];
    for (let c = 0; c < 3; c++) out.set(n, t + c * 3);
  }
  return out;
}

/**
 * MikkTSpace over the triangles with area only. The `mikktspace` WebAssembly port traps (a Rust
 * panic, "unreachable") when every triangle is degenerate, and the instance is corrupt afterwards
 * (later calls fault on memory); zero-area triangles are never hit by a ray anyway. They get a unit
 * tangent perpendicular to their normal (any one will do).
 */
function generateSkippingDegenerate(generate: GenerateTangents, positions: Float32Array, normals: Float32Array, uvs: Float32Array): Float32Array {
  const triangles = positions.length / 9;
  const keep: number[] = [];
  for (let t = 0; t < triangles; t++) {
    const p = 9 * t;
    const e1 = [positions[p + 3] - positions[p], positions[p + 4] - positions[p + 1], positions[p + 5] - positions[p + 2]];
    const e2 = [positions[p + 6] - positions[p], positions[p + 7] - positions[p + 1], positions[p + 8] - positions[p + 2]];
    const area = Math.hypot(e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]);
    if (area > 0 && Number.isFinite(area)) keep.push(t);
  }
  const out = new Float32Array(triangles * 12);
  for (let c = 0; c < triangles * 3; c++) {
    const n = [normals[3 * c], normals[3 * c + 1], normals[3 * c + 2]];
    const axis = Math.abs(n[0]) < 0.9 ? [1, 0, 0] : [0, 1, 0];
    const t = [axis[1] * n[2] - axis[2] * n[1], axis[2] * n[0] - axis[0] * n[2], axis[0] * n[1] - axis[1] * n[0]];
    const len = Math.hypot(t[0], t[1], t[2]) || 1;
    out.set([t[0] / len, t[1] / len, t[2] / len, 1], 4 * c);
  }
  if (keep.length === 0) return out;
  const all = keep.length === triangles;
  const pick = (values: Float32Array, size: number): Float32Array => {
    if (all) return values;
    const picked = new Float32Array(keep.length * 3 * size);
    keep.forEach((t, k) => picked.set(values.subarray(t * 3 * size, (t + 1) * 3 * size), k * 3 * size));
    return picked;
  };
  const generated = generate(pick(positions, 3), pick(normals, 3), pick(uvs, 2));
  keep.forEach((t, k) => out.set(generated.subarray(k * 12, (k + 1) * 12), t * 12));
  return out;
}

/**
 * Welds corners whose every attribute is bitwise equal: `remap` gives each corner its vertex,
 * `unique` each vertex its first corner. An open-addressing hash table over the attributes' 32-bit
 * words keeps this linear in time and free of per-corner allocations (million-triangle meshes).
 */
function weld(streams: Array<{ values: Float32Array; size: number }>, cornerCount: number): { remap: Uint32Array; unique: number[] } {
  const words = streams.map((s) => ({ bits: new Uint32Array(s.values.buffer, s.values.byteOffset, s.values.length), size: s.size }));
  const hash = (c: number): number => {
    let h = 0x811c9dc5;
    for (const { bits, size } of words) {
      for (let k = 0; k < size; k++) h = Math.imul(h ^ bits[c * size + k]!, 0x01000193);
    }
    return (h ^ (h >>> 15)) >>> 0;
  };
  const same = (a: number, b: number): boolean => {
    for (const { bits, size } of words) {
      for (let k = 0; k < size; k++) if (bits[a * size + k] !== bits[b * size + k]) return false;
    }
    return true;
  };
  let capacity = 1;
  while (capacity < 2 * cornerCount) capacity *= 2;
  const mask = capacity - 1;
  const table = new Int32Array(capacity).fill(-1); // vertex index, or -1 for an empty slot
  const remap = new Uint32Array(cornerCount);
  const unique: number[] = [];
  for (let c = 0; c < cornerCount; c++) {
    let slot = hash(c) & mask;
    for (;;) {
      const vertex = table[slot]!;
      if (vertex < 0) {
        table[slot] = unique.length;
        remap[c] = unique.length;
        unique.push(c);
        break;
      }
      if (same(c, unique[vertex]!)) {
        remap[c] = vertex;
        break;
      }
      slot = (slot + 1) & mask;
    }
  }
  return { remap, unique };
}

/**
 * Returns `streams` with MikkTSpace tangents for UV set `texCoord` (0 or 1), re-indexed; adds flat
 * normals first when the mesh has none (a tangent frame needs a normal).
 */
export async function withMikkTSpaceTangents(streams: VertexStreams, texCoord: number): Promise<VertexStreams> {
  const uvs = texCoord === 1 ? streams.uvs1 : streams.uvs;
  if (uvs === undefined) throw new RangeError(`texCoord ${texCoord} has no uvs`);
  const generate = await (generator ??= loadGenerator());
  const corners = streams.indices;
  const cornerPositions = unweld(streams.positions, 3, corners);
  const cornerNormals = streams.normals === undefined ? flatNormals(cornerPositions) : unweld(streams.normals, 3, corners);
  const cornerUvs = unweld(uvs, 2, corners);
  const tangents = generateSkippingDegenerate(generate, cornerPositions, cornerNormals, cornerUvs);
  for (let w = 3; w < tangents.length; w += 4) tangents[w] = -tangents[w]!;

  const perCorner: Array<{ name: keyof VertexStreams; values: Float32Array; size: number }> = [
    { name: 'positions', values: cornerPositions, size: 3 },
    { name: 'normals', values: cornerNormals, size: 3 },
    { name: 'tangents', values: tangents, size: 4 },
  ];
  if (streams.uvs !== undefined) perCorner.push({ name: 'uvs', values: texCoord === 0 ? cornerUvs : unweld(streams.uvs, 2, corners), size: 2 });
  if (streams.uvs1 !== undefined) perCorner.push({ name: 'uvs1', values: texCoord === 1 ? cornerUvs : unweld(streams.uvs1, 2, corners), size: 2 });
  if (streams.colors !== undefined) {
    const size = streams.colors.length / (streams.positions.length / 3);
    perCorner.push({ name: 'colors', values: unweld(streams.colors, size, corners), size });
  }
  const { remap, unique } = weld(perCorner, corners.length);
  const out: VertexStreams = { ...streams, indices: remap };
  for (const s of perCorner) {
    const welded = new Float32Array(unique.length * s.size);
    unique.forEach((corner, v) => welded.set(s.values.subarray(corner * s.size, (corner + 1) * s.size), v * s.size));
    (out as unknown as Record<string, Float32Array>)[s.name] = welded;
  }
  return out;
}
