/**
 * Geometry updates of a live renderer (the next pose of an animation): new vertex positions (and
 * normals, tangents) of existing meshes and new instance transforms, with the topology kept (same
 * vertex counts, same triangles, same attributes, same materials). Everything is validated and
 * packed before anything is written, so a refused update leaves the renderer as it was.
 */
import { describe, fail, isArrayLike } from '../../errors/validate.ts';
import { GpuRendererError } from '../../errors/gpu-renderer-error.ts';
import { INSTANCE_FLAG_NEGATIVE_DETERMINANT } from '../../gpu-layout/constants.ts';
import { instanceLayout } from '../../gpu-layout/records.ts';
import { fieldOf } from '../../gpu-layout/struct-layout.ts';
import { affineFromColumnMajor, type NormalizedInstance } from '../../scene/instance.ts';
import { normalizeWavefrontMesh, type NormalizedMesh } from '../../scene/mesh.ts';
import type { NormalizedScene } from '../../scene/normalize-scene.ts';
import { flattenPrimitives, type SceneBounds } from './flatten-primitives.ts';
import { bottomLevelRoots, refitBottomLevels, type BottomLevels } from './instancing.ts';
import { buildLightTable, type LightTable } from './light-table.ts';
import { packVertexStreams } from './pack-vertices.ts';
import type { PreparedScene } from './prepare-scene.ts';
import type { BvhUpdateMode } from './scene-acceleration.ts';
import { patchTopLevel, type TopLevelUpdate } from './top-level-patch.ts';

/** New vertex data of one mesh: positions, and normals / tangents where the mesh has them (omitted: kept). */
export interface WavefrontMeshGeometryUpdate {
  positions: ArrayLike<number>;
  normals?: ArrayLike<number>;
  tangents?: ArrayLike<number>;
}

/** A new placement of one instance: its object-to-world matrix (column-major 4x4, affine). */
export interface WavefrontInstanceTransformUpdate {
  transform: ArrayLike<number>;
}

export interface WavefrontGeometryUpdate {
  /** One entry per mesh of the scene, in order (null or undefined keeps a mesh as it is). */
  meshes?: ReadonlyArray<WavefrontMeshGeometryUpdate | null | undefined>;
  /** One entry per instance of the scene, in order (null or undefined keeps it). */
  instances?: ReadonlyArray<WavefrontInstanceTransformUpdate | null | undefined>;
  /**
   * How the BVH follows: 'refit' (default) keeps its topology and recomputes every box on the GPU
   * (fast; its quality drifts as the pose departs from the built one), 'rebuild' builds a new tree
   * in the renderer's accelerationBuildMode.
   */
  bvh?: BvhUpdateMode;
}

export interface WavefrontGeometryUpdateStats {
  bvh: BvhUpdateMode;
  /** Wall time of the BVH refit or rebuild, ms. */
  accelerationMs: number;
  /** Wall time of the whole update (validation, packing, uploads, BVH), ms. */
  totalMs: number;
  /**
   * How the top level followed: 'patched' (only instances moved and the tree was refitted: the
   * moved instances' records alone were rewritten) or 'flattened' (moved meshes, or a rebuild).
   */
  topLevel: 'patched' | 'flattened';
  /** Top-level records written: the moved instances' under 'patched', every record under 'flattened'. */
  topLevelRecordsWritten: number;
}

/** What an update writes, all packed before the first write. */
export interface PackedGeometryUpdate {
  scene: NormalizedScene;
  topLevel: TopLevelUpdate;
  bounds: SceneBounds;
  bvh: BvhUpdateMode;
  vertexStreams: Uint32Array | null;
  instances: ArrayBuffer | null;
  lights: LightTable | null;
  /** Bottom levels refitted to moved shared meshes (null when none moved). */
  bottomLevels: BottomLevels | null;
}

function meshUpdate(mesh: NormalizedMesh, input: unknown, index: number): NormalizedMesh {
  const field = `meshes[${index}]`;
  if (typeof input !== 'object' || input === null) fail('INVALID_MESH', field, `expected { positions, normals?, tangents? } or null, got ${describe(input)}`);
  for (const key of Object.keys(input)) {
    if (!['positions', 'normals', 'tangents'].includes(key)) fail('INVALID_MESH', `${field}.${key}`, 'a geometry update changes positions, normals and tangents only');
  }
  const u = input as WavefrontMeshGeometryUpdate;
  if (!isArrayLike(u.positions) || u.positions.length !== 3 * mesh.vertexCount) {
    fail('INVALID_MESH', `${field}.positions`, `expected ${3 * mesh.vertexCount} numbers (the mesh's ${mesh.vertexCount} vertices), got ${describe(u.positions)}`);
  }
  if (u.normals !== undefined && !mesh.normals) fail('INVALID_MESH', `${field}.normals`, 'the mesh was created without normals');
  if (u.tangents !== undefined && !mesh.tangents) fail('INVALID_MESH', `${field}.tangents`, 'the mesh was created without tangents');
  // The mesh validator checks values and lengths against the kept triangles (the material is not reread).
  const checked = normalizeWavefrontMesh(
    { positions: u.positions, indices: mesh.indices, ...(u.normals !== undefined ? { normals: u.normals } : {}), ...(u.tangents !== undefined ? { tangents: u.tangents } : {}), material: 0 },
    index,
    field,
    { materialCount: 1 },
  );
  return { ...mesh, positions: checked.positions, normals: checked.normals ?? mesh.normals, tangents: checked.tangents ?? mesh.tangents };
}

function instanceUpdate(inst: NormalizedInstance, input: unknown, index: number): NormalizedInstance {
  const field = `instances[${index}]`;
  if (typeof input !== 'object' || input === null) fail('INVALID_INSTANCE', field, `expected { transform } or null, got ${describe(input)}`);
  for (const key of Object.keys(input)) {
    if (key !== 'transform') fail('INVALID_INSTANCE', `${field}.${key}`, 'a geometry update changes the transform only');
  }
  const { objectToWorld, normalToWorld, determinant } = affineFromColumnMajor((input as WavefrontInstanceTransformUpdate).transform, `${field}.transform`);
  // A literal, not a spread: moving 10,000 placements per frame makes 10,000 of these.
  return { id: inst.id, mesh: inst.mesh, material: inst.material, objectToWorld, normalToWorld, determinant };
}

function entries<T>(value: unknown, count: number, field: 'meshes' | 'instances'): ReadonlyArray<T | null | undefined> | null {
  if (value === undefined) return null;
  const code = field === 'meshes' ? 'INVALID_MESH' : 'INVALID_INSTANCE';
  if (!Array.isArray(value)) fail(code, field, `expected an array, got ${describe(value)}`);
  if (value.length !== count) fail(code, field, `expected one entry (or null) per ${field === 'meshes' ? 'mesh' : 'instance'} of the scene: ${count}, got ${value.length}`);
  return value as ReadonlyArray<T | null | undefined>;
}

// Word offsets of the fields patchInstances rewrites, from the layout.
const instanceWords = instanceLayout.size / 4;
const at = (name: string): number => fieldOf(instanceLayout, name).offset / 4;
const patched = { objectToWorld: [at('objectToWorld0'), at('objectToWorld1'), at('objectToWorld2')], normalToWorld: [at('normalToWorld0'), at('normalToWorld1'), at('normalToWorld2')], flags: at('flags') };

/**
 * The packed instance records with new transforms (the rest of each record is kept), written
 * word by word: moving 10,000 placements per frame patches 10,000 records.
 */
function patchInstances(records: ArrayBuffer, scene: NormalizedScene): ArrayBuffer {
  const out = records.slice(0);
  const f = new Float32Array(out);
  const u = new Uint32Array(out);
  scene.instances.forEach((inst, i) => {
    const o = i * instanceWords;
    const m = inst.objectToWorld;
    const n = inst.normalToWorld;
    for (let r = 0; r < 3; r++) {
      const w = o + patched.objectToWorld[r]!;
      f[w] = m[4 * r]!;
      f[w + 1] = m[4 * r + 1]!;
      f[w + 2] = m[4 * r + 2]!;
      f[w + 3] = m[4 * r + 3]!;
      const v = o + patched.normalToWorld[r]!;
      f[v] = n[3 * r]!;
      f[v + 1] = n[3 * r + 1]!;
      f[v + 2] = n[3 * r + 2]!;
      f[v + 3] = 0;
    }
    const flags = u[o + patched.flags]!;
    u[o + patched.flags] = inst.determinant < 0 ? flags | INSTANCE_FLAG_NEGATIVE_DETERMINANT : flags & ~INSTANCE_FLAG_NEGATIVE_DETERMINANT;
  });
  return out;
}

/**
 * Validates an update against the scene and packs everything it changes. Throws typed errors
 * naming the field (nothing is written by this function).
 */
export function packGeometryUpdate(scene: NormalizedScene, prepared: PreparedScene, update: WavefrontGeometryUpdate): PackedGeometryUpdate {
  if (typeof update !== 'object' || update === null) fail('INVALID_OPTION', 'update', `expected { meshes?, instances?, bvh? }, got ${describe(update)}`);
  for (const key of Object.keys(update)) {
    if (!['meshes', 'instances', 'bvh'].includes(key)) fail('INVALID_OPTION', key, 'unknown geometry update key (meshes, instances, bvh)');
  }
  const bvh = update.bvh ?? 'refit';
  if (bvh !== 'refit' && bvh !== 'rebuild') fail('INVALID_OPTION', 'bvh', `expected "refit" or "rebuild", got ${describe(bvh)}`);
  const meshInputs = entries<WavefrontMeshGeometryUpdate>(update.meshes, scene.meshes.length, 'meshes');
  const instanceInputs = entries<WavefrontInstanceTransformUpdate>(update.instances, scene.instances.length, 'instances');
  const meshes = meshInputs ? scene.meshes.map((mesh, i) => (meshInputs[i] == null ? mesh : meshUpdate(mesh, meshInputs[i], i))) : scene.meshes;
  const instances = instanceInputs ? scene.instances.map((inst, i) => (instanceInputs[i] == null ? inst : instanceUpdate(inst, instanceInputs[i], i))) : scene.instances;
  const next: NormalizedScene = { ...scene, meshes, instances };
  const infoOffset = (texture: number, srgb: boolean): number => prepared.atlas.infoOffset(texture, srgb);
  const meshesMoved = meshInputs?.some((u) => u != null) ?? false;
  // Only instances moved and the tree is refitted: their records alone are rewritten.
  let topLevel: TopLevelUpdate;
  if (!meshesMoved && bvh === 'refit') {
    const moved: number[] = [];
    instanceInputs?.forEach((u, i) => {
      if (u != null) moved.push(i);
    });
    topLevel = { patch: patchTopLevel(next, prepared, moved) };
  } else {
    topLevel = { flat: flattenPrimitives(next, infoOffset, prepared.instancing, prepared.bottomLevels ? bottomLevelRoots(prepared.bottomLevels) : null) };
  }
  let lights: LightTable | null = null;
  if (prepared.lightCount > 0) {
    lights = buildLightTable(next, infoOffset);
    if (lights.count !== prepared.lightCount) {
      throw new GpuRendererError('INVALID_STATE', `the update changes the emitting triangles (${prepared.lightCount} -> ${lights.count} with positive power); create a new renderer for it`, { field: 'meshes' });
    }
  }
  // Shared meshes that moved: their bottom levels are refitted on a copy (applied with the rest).
  const moved = new Set<number>();
  meshInputs?.forEach((u, i) => {
    if (u != null) moved.add(i);
  });
  let bottomLevels: BottomLevels | null = null;
  const bottom = prepared.bottomLevels;
  if (bottom && prepared.instancing.bottomLevels.some((b) => moved.has(b.mesh))) {
    bottomLevels = { ...bottom, primitives: bottom.primitives.slice(0), nodes: bottom.nodes.slice(0) };
    refitBottomLevels(next, prepared.instancing, bottomLevels, moved);
  }
  return {
    scene: next,
    topLevel,
    bounds: topLevel.flat ? topLevel.flat.bounds : topLevel.patch.bounds,
    bottomLevels,
    bvh,
    vertexStreams: meshInputs ? packVertexStreams(meshes).vertexStreams : null,
    instances: instanceInputs ? patchInstances(prepared.instances, next) : null,
    lights,
  };
}
