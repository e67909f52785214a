import { buildBvhAsync, type BvhBuildResult } from '../../accel/bvh-builder.ts';
import { bvhParentLinks, packPrimitives, packWavefrontBvhNodes } from '../../accel/triangle-packing.ts';
import { Vec4Heap } from '../../gpu-layout/vec4-heap.ts';
import { buildTextureAtlas, type TextureAtlas } from '../../materials/textures/texture-atlas.ts';
import type { AtlasLimits } from '../../materials/textures/atlas-packer.ts';
import type { NormalizedScene } from '../../scene/normalize-scene.ts';
import { flattenPrimitives, type SceneBounds } from './flatten-primitives.ts';
import { bottomLevelRoots, buildBottomLevels, planInstancing, type BottomLevels, type InstancingMode, type InstancingPlan } from './instancing.ts';
import { buildLightTable } from './light-table.ts';
import { packInstances } from './pack-instances.ts';
import { packMaterialTables, packMaterials, planMaterials, textureUsages, type MaterialFeatureUses, type TextureInfoOffsets } from './pack-materials.ts';
import { packVertexStreams } from './pack-vertices.ts';

/** Everything the path tracer uploads for a scene, packed on the CPU. */
export interface PreparedScene {
  primitives: ArrayBuffer;
  bvhNodes: ArrayBuffer;
  bvhParents: Uint32Array;
  alphaPrimitives: ArrayBuffer;
  instances: ArrayBuffer;
  indices: Uint32Array;
  vertexStreams: Uint32Array;
  materials: ArrayBuffer;
  atlas: TextureAtlas;
  lights: ArrayBuffer;
  lightCount: number;
  lightPower: number;
  /** Records of the top level (flattened triangles, placements of shared meshes, analytic shapes). */
  primitiveCount: number;
  triangleCount: number;
  /** Which placements go through bottom-level trees, and the trees (null when none do). */
  instancing: InstancingPlan;
  bottomLevels: BottomLevels | null;
  /** World box of each instance's geometry (6 per instance), what a patch of moved instances keeps of the rest. */
  instanceBounds: Float64Array;
  /** The placements' transform records, for primitive slots from `base` (rewritten when placements move). */
  placementTransforms: { base: number; records: ArrayBuffer };
  bvh: { nodeCount: number; depth: number; sahCost: number; buildTimeMs: number };
  /**
   * How the BVH is built. 'cpu-upload': `bvhNodes`, `bvhParents` and `primitives` (in BVH order,
   * slot s = flat primitive order[s]) are the CPU build's, ready to upload. 'gpu': `primitives`
   * holds the records in scene order for the GPU builder (src/accel/gpu-build/), `bvhNodes` and
   * `bvhParents` are empty and `bvh` is filled in once the GPU has built the tree.
   */
  acceleration: { mode: AccelerationBuildMode; order: Uint32Array | null };
  sceneCenter: [number, number, number];
  sceneRadius: number;
  /** Which optional shader features the scene needs (the rest are compiled out). */
  uses: { analyticShapes: boolean; instancing: boolean; alphaTest: boolean; textures: boolean; emissiveLights: boolean; materials: MaterialFeatureUses };
  warnings: string[];
}

/** Where the BVH is built: on the CPU and uploaded (default), or on the GPU (src/accel/gpu-build/). */
export type AccelerationBuildMode = 'cpu-upload' | 'gpu';

/** The material half of a prepared scene: the material heap and the texture atlas, independent of geometry. */
export interface PreparedMaterials {
  heap: Vec4Heap;
  atlas: TextureAtlas;
  infoOffset: TextureInfoOffsets;
  materialOffsets: number[];
  objectMaterialOffsets: number[];
  uses: { textures: boolean; materials: MaterialFeatureUses };
  warnings: string[];
}

/** Packs the materials (of the scene and its analytic objects) and the texture atlas. */
export function prepareMaterials(scene: NormalizedScene, limits: AtlasLimits, options: { energyCompensation?: boolean } = {}): PreparedMaterials {
  const warnings: string[] = [];
  const heap = new Vec4Heap();
  const objectMaterials = scene.sceneObjects.map((o) => o.material);
  const materialPlan = planMaterials([...scene.materials, ...objectMaterials], {
    energyCompensation: options.energyCompensation === true,
    fields: [...scene.materialFields, ...scene.sceneObjects.map((_, i) => `sceneObjects[${i}]`)],
  });
  // The material tables open the heap: the kernels find them at MATERIAL_TABLES_OFFSET.
  packMaterialTables(heap, materialPlan);
  const usages = textureUsages([...scene.materials, ...objectMaterials]);
  const atlas = buildTextureAtlas(scene, usages, heap, limits, warnings);
  const infoOffset = (texture: number, srgb: boolean): number => atlas.infoOffset(texture, srgb);
  const materialOffsets = packMaterials(heap, scene.materials, infoOffset, materialPlan);
  const objectMaterialOffsets = packMaterials(heap, objectMaterials, infoOffset, materialPlan);
  return { heap, atlas, infoOffset, materialOffsets, objectMaterialOffsets, uses: { textures: usages.length > 0, materials: materialPlan.uses }, warnings };
}

/**
 * Packs the geometry against prepared materials: vertex streams, world-space primitives and (in
 * 'cpu-upload' mode) their BVH, instance records and the emissive triangles. A scene whose meshes
 * and instances are replaced (`updateScene`) re-runs only this half.
 */
export async function prepareGeometry(
  scene: NormalizedScene,
  materials: PreparedMaterials,
  options: { signal?: AbortSignal; accelerationBuildMode?: AccelerationBuildMode; instancing?: InstancingMode } = {},
): Promise<PreparedScene> {
  const { infoOffset } = materials;
  const streams = packVertexStreams(scene.meshes);
  const lights = buildLightTable(scene, infoOffset);
  const plan = planInstancing(scene, options.instancing);
  // The top level's alpha records come first (at least one record, as every buffer).
  const bottomLevels = plan.bottomLevels.length > 0 ? await buildBottomLevels(scene, plan, infoOffset, Math.max(1, plan.topAlphaTriangles), options.signal ? { signal: options.signal } : {}) : null;
  const flat = flattenPrimitives(scene, infoOffset, plan, bottomLevels ? bottomLevelRoots(bottomLevels) : null);
  const gpu = options.accelerationBuildMode === 'gpu';
  const cpuBvh = gpu ? null : await buildBvhAsync(flat.boundsTriangles, options.signal ? { signal: options.signal } : {});
  const bvh = cpuBvh ?? gpuBuildPending(flat.count);
  const nodes = cpuBvh ? packWavefrontBvhNodes(cpuBvh) : new ArrayBuffer(0);
  const { sceneCenter, sceneRadius } = sceneExtent(scene, flat.bounds);
  return {
    primitives: packPrimitives(flat, bvh.triangleOrder),
    bvhNodes: nodes,
    bvhParents: gpu ? new Uint32Array(0) : bvhParentLinks(nodes, bvh.nodeCount),
    alphaPrimitives: bottomLevels ? concatBuffers(flat.alphaPrimitives, bottomLevels.alphaPrimitives) : flat.alphaPrimitives,
    instances: packInstances(scene, streams, materials.materialOffsets, materials.objectMaterialOffsets, lights.lightBase),
    indices: streams.indices,
    vertexStreams: streams.vertexStreams,
    materials: materials.heap.finish(),
    atlas: materials.atlas,
    lights: lights.records,
    lightCount: lights.count,
    lightPower: lights.totalPower,
    primitiveCount: flat.count,
    triangleCount: scene.triangleCount,
    instancing: plan,
    bottomLevels,
    instanceBounds: flat.instanceBounds,
    placementTransforms: { base: flat.placementTransformBase, records: flat.placementTransforms },
    bvh: { nodeCount: bvh.nodeCount, depth: bvh.depth, sahCost: bvh.sahCost, buildTimeMs: bvh.buildTimeMs },
    acceleration: { mode: gpu ? 'gpu' : 'cpu-upload', order: gpu ? null : bvh.triangleOrder },
    sceneCenter,
    sceneRadius,
    uses: { analyticShapes: scene.sceneObjects.length > 0, instancing: bottomLevels !== null, alphaTest: plan.alphaTriangles > 0, textures: materials.uses.textures, emissiveLights: lights.count > 0, materials: materials.uses.materials },
    warnings: materials.warnings,
  };
}

export async function prepareScene(
  scene: NormalizedScene,
  limits: AtlasLimits,
  options: { signal?: AbortSignal; energyCompensation?: boolean; accelerationBuildMode?: AccelerationBuildMode; instancing?: InstancingMode } = {},
): Promise<PreparedScene> {
  return prepareGeometry(scene, prepareMaterials(scene, limits, options), options);
}

/** Centre and radius of the scene's bounding sphere (radius 1 for an empty scene). */
export function sceneExtent(scene: NormalizedScene, bounds: SceneBounds): { sceneCenter: [number, number, number]; sceneRadius: number } {
  const { min, max } = bounds;
  const empty = scene.triangleCount + scene.sceneObjects.length === 0;
  const sceneCenter: [number, number, number] = [0.5 * (min[0] + max[0]), 0.5 * (min[1] + max[1]), 0.5 * (min[2] + max[2])];
  const sceneRadius = empty ? 1 : Math.max(1e-6, 0.5 * Math.hypot(max[0] - min[0], max[1] - min[1], max[2] - min[2]));
  return { sceneCenter, sceneRadius };
}

function concatBuffers(a: ArrayBuffer, b: ArrayBuffer): ArrayBuffer {
  const out = new Uint8Array(a.byteLength + b.byteLength);
  out.set(new Uint8Array(a), 0);
  out.set(new Uint8Array(b), a.byteLength);
  return out.buffer;
}

/** Before a GPU build: scene order (the identity) and no nodes yet. */
function gpuBuildPending(count: number): Pick<BvhBuildResult, 'triangleOrder' | 'nodeCount' | 'depth' | 'sahCost' | 'buildTimeMs'> {
  return { triangleOrder: Uint32Array.from({ length: count }, (_, i) => i), nodeCount: 0, depth: 0, sahCost: 0, buildTimeMs: 0 };
}
