import { INDEX_NONE, LIGHT_FLAG_DOUBLE_SIDED, PORTAL_MODE_GUIDE, PORTAL_MODE_GUIDE_AND_GATE } from '../gpu-layout/constants.ts';
import {
  areaLightLayout,
  environmentPortalLayout,
  environmentTableEntryLayout,
  lightingUniformsLayout,
  lightRecordLayout,
  lightSelectionEntryLayout,
  lightTreeNodeLayout,
  punctualLightLayout,
} from '../gpu-layout/records.ts';
import { fieldOf, writeStruct } from '../gpu-layout/struct-layout.ts';
import { buildAliasTable } from './alias-table.ts';
import { packAreaLights, type AreaLight } from './area-lights.ts';
import type { EnvironmentMap } from './environment-map.ts';
import { buildEnvironmentSampler, type EnvironmentSampler } from './environment-sampling.ts';
import { areaLightBounds, punctualLightBounds, triangleLightBounds } from './light-sampler.ts';
import { buildLightTree, LIGHT_TREE_NONE, packLightTree, type LightTree, type LightTreeItem } from './light-tree.ts';
import { AUTO_LIGHT_TREE_THRESHOLD, type LightingConfig } from './lighting-options.ts';
import { buildPortalEnvironmentSampler, packPortals, PORTAL_GUIDE_PROBABILITY } from './portals.ts';
import { packPunctualLights, type PunctualLight } from './punctual-lights.ts';
import { sunSolidAngle } from './sun-light.ts';
import { luminance, type Vec3 } from './vec3.ts';

/**
 * Everything the GPU lights with, packed for the path tracer: one `lights` heap of vec4 cells, the
 * `LightingUniforms` that say where each part of it starts, the environment map's radiance (the
 * `environmentTexture`), and which optional shader features the scene needs. Heap layout, in order:
 *
 *   LightSelectionEntry[boundedCount]   per bounded light: power alias bin, pmf, light-tree leaf
 *   LightRecord[triangleCount]          emissive triangles (src/pathtracer/scene/light-table.ts)
 *   AreaLight[areaCount]                rectangle, disk and sphere lights
 *   PunctualLight[punctual + directional]  point and spot lights, then directional lights
 *   LightTreeNode[]                     the light hierarchy over the bounded lights (tree mode)
 *   EnvironmentTableEntry[H + W H]      the map's marginal and conditional alias tables
 *   EnvironmentPortal[portalCount], then the portals' densities and summed-area tables (f32)
 *
 * Bounded lights (global index g): emissive triangles [0, T), area lights [T, T + A), point and
 * spot lights [T + A, T + A + P). Next-event estimation picks the environment, the sun, a
 * directional light or a bounded light with probabilities proportional to estimated power (each
 * present group keeps at least MIN_GROUP_PROBABILITY, so every strategy stays alive; any split is
 * unbiased, it only steers variance).
 */

/** Table cells above which the environment's sampling tables are built coarser than the map. */
export const MAX_ENVIRONMENT_TABLE_CELLS = 1 << 21;
/** Smallest probability of a light group that is present (environment, sun, directional, bounded). */
export const MIN_GROUP_PROBABILITY = 0.05;
/** Size of the constant map a uniform environment colour becomes when portals steer its sampling. */
const UNIFORM_PORTAL_MAP_SIZE: [number, number] = [16, 8];

export interface GpuLightingInput {
  config: LightingConfig;
  /** Emissive triangles: LightRecords (light-table.ts) and their count. */
  triangles: { records: ArrayBuffer; count: number };
  /** The scene's bounding sphere (power estimates of infinite lights). */
  sceneCenter: readonly number[];
  sceneRadius: number;
}

export interface LightGroupProbabilities {
  environment: number;
  sun: number;
  directional: number;
  bounded: number;
}

export interface GpuLighting {
  heap: ArrayBuffer;
  /** LightingUniforms. */
  uniforms: ArrayBuffer;
  /** FrameUniforms.environmentSelectProbability. */
  environmentSelectProbability: number;
  /** Uniform environment radiance (FrameUniforms.environmentRadiance); zero when a map lights the scene. */
  uniformEnvironment: Vec3;
  /** Bounded lights: emissive triangles, area lights, point and spot lights. */
  boundedCount: number;
  directionalCount: number;
  /** The map in `environmentTexture`, or null (a 1 x 1 black texture is bound). */
  environmentMap: EnvironmentMap | null;
  environmentSampler: EnvironmentSampler | null;
  tree: LightTree | null;
  probabilities: LightGroupProbabilities;
  uses: {
    environment: boolean;
    environmentMap: boolean;
    sun: boolean;
    portals: boolean;
    punctualLights: boolean;
    areaLights: boolean;
    lightTree: boolean;
  };
}

/** Probabilities proportional to power, each present group at least MIN_GROUP_PROBABILITY. */
export function lightGroupProbabilities(power: LightGroupProbabilities): LightGroupProbabilities {
  const keys = ['environment', 'sun', 'directional', 'bounded'] as const;
  const present = keys.filter((k) => power[k] > 0 && Number.isFinite(power[k]));
  const out: LightGroupProbabilities = { environment: 0, sun: 0, directional: 0, bounded: 0 };
  if (present.length === 0) return out;
  const total = present.reduce((a, k) => a + power[k], 0);
  let sum = 0;
  for (const k of present) {
    out[k] = present.length === 1 ? 1 : Math.max(MIN_GROUP_PROBABILITY, power[k] / total);
    sum += out[k];
  }
  for (const k of present) out[k] /= sum;
  return out;
}

/** Power estimate of an area light (area x luminance x pi per emitting side). */
function areaLightPower(l: AreaLight): number {
  return l.area * luminance(l.radiance) * Math.PI * (l.type !== 'sphere' && l.twoSided ? 2 : 1);
}

/** Power estimate of a point or spot light: intensity over the sphere or the outer cone. */
function punctualLightPower(l: PunctualLight): number {
  const solidAngle = l.type === 'spot' ? 2 * Math.PI * (1 - Math.cos(l.outerConeAngle)) : 4 * Math.PI;
  return luminance(l.intensity) * solidAngle;
}

function constantMap(radiance: Vec3): EnvironmentMap {
  const [w, h] = UNIFORM_PORTAL_MAP_SIZE;
  const data = new Float32Array(w * h * 4);
  for (let t = 0; t < w * h; t++) data.set([radiance[0], radiance[1], radiance[2], 1], 4 * t);
  return { width: w, height: h, data, intensity: 1, rotationRadians: 0 };
}

interface TriangleView {
  bounds: LightTreeItem['bounds'][];
  power: Float64Array;
}

/** Power and tree bounds of the emissive triangles, read back from their LightRecords. */
function triangleLights(records: ArrayBuffer, count: number, withBounds: boolean): TriangleView {
  const view = new DataView(records);
  const f = (name: string): number => fieldOf(lightRecordLayout, name).offset;
  const [o0, o1, o2, oe, oa, of] = [f('v0'), f('e1'), f('e2'), f('emission'), f('area'), f('flags')];
  const vec = (base: number, at: number): Vec3 => [view.getFloat32(base + at, true), view.getFloat32(base + at + 4, true), view.getFloat32(base + at + 8, true)];
  const power = new Float64Array(count);
  const bounds: LightTreeItem['bounds'][] = [];
  for (let t = 0; t < count; t++) {
    const base = t * lightRecordLayout.size;
    const emission = vec(base, oe);
    const area = view.getFloat32(base + oa, true);
    const doubleSided = (view.getUint32(base + of, true) & LIGHT_FLAG_DOUBLE_SIDED) !== 0;
    power[t] = area * luminance(emission) * Math.PI * (doubleSided ? 2 : 1);
    if (withBounds) {
      const v0 = vec(base, o0);
      const e1 = vec(base, o1);
      const e2 = vec(base, o2);
      const v1 = [v0[0] + e1[0], v0[1] + e1[1], v0[2] + e1[2]];
      const v2 = [v0[0] + e2[0], v0[1] + e2[1], v0[2] + e2[2]];
      bounds.push(triangleLightBounds({ triangle: t, v0, v1, v2, area, emission, doubleSided }));
    }
  }
  return { bounds, power };
}

/** Packs the scene's lights and environment for the GPU (see the module comment). */
export function buildGpuLighting(input: GpuLightingInput): GpuLighting {
  const { config } = input;
  const R = input.sceneRadius;
  const crossSection = Math.PI * R * R;

  // Environment: a map (given, baked sky, or a uniform colour that portals steer), or uniform.
  let environmentMap: EnvironmentMap | null = null;
  let uniformEnvironment: Vec3 = [0, 0, 0];
  const sun = config.environment.kind === 'map' ? config.environment.sun : null;
  if (config.environment.kind === 'map') environmentMap = config.environment.map;
  else if (config.environment.kind === 'uniform') {
    if (config.portals.length > 0) environmentMap = constantMap(config.environment.radiance);
    else uniformEnvironment = config.environment.radiance;
  }
  const sampler = environmentMap ? buildEnvironmentSampler(environmentMap, { maxTableCells: MAX_ENVIRONMENT_TABLE_CELLS, uniform: config.environmentSampling === 'uniform' }) : null;
  // The environment's power comes from its radiance, whichever tables sample it.
  const radianceSampler = environmentMap && config.environmentSampling === 'uniform' ? buildEnvironmentSampler(environmentMap, { maxTableCells: MAX_ENVIRONMENT_TABLE_CELLS }) : sampler;
  const mapUsable = radianceSampler !== null && radianceSampler.weightIntegral > 0;
  // Mean radiance over the sphere: integral of L d omega = 2 pi^2 x weightIntegral x intensity.
  const environmentMeanLuminance = mapUsable ? (Math.PI / 2) * radianceSampler.weightIntegral * environmentMap!.intensity : luminance(uniformEnvironment);
  const portalsUsed = mapUsable && config.portals.length > 0;

  // Bounded and directional lights.
  const punctualBounded = config.punctual.filter((l) => l.type !== 'directional' && luminance(l.intensity) > 0);
  const directional = config.punctual.filter((l) => l.type === 'directional' && luminance(l.intensity) > 0);
  const T = input.triangles.count;
  const A = config.area.length;
  const P = punctualBounded.length;
  const boundedCount = T + A + P;
  const useTree = boundedCount > 0 && (config.lightSampler === 'tree' || (config.lightSampler === 'auto' && boundedCount > AUTO_LIGHT_TREE_THRESHOLD));
  const triangles = triangleLights(input.triangles.records, T, useTree);
  const boundedPower = new Float64Array(boundedCount);
  boundedPower.set(triangles.power, 0);
  config.area.forEach((l, i) => (boundedPower[T + i] = areaLightPower(l)));
  punctualBounded.forEach((l, i) => (boundedPower[T + A + i] = punctualLightPower(l)));
  const boundedTotal = boundedPower.reduce((a, b) => a + b, 0);

  const probabilities = lightGroupProbabilities({
    environment: environmentMeanLuminance * 4 * Math.PI * crossSection,
    sun: sun ? luminance(sun.radiance) * sunSolidAngle(sun) * crossSection : 0,
    directional: directional.reduce((a, l) => a + luminance(l.intensity) * crossSection, 0),
    bounded: boundedTotal,
  });

  let tree: LightTree | null = null;
  if (useTree && probabilities.bounded > 0) {
    const items: LightTreeItem[] = triangles.bounds.map((bounds, g) => ({ light: g, bounds }));
    config.area.forEach((l, i) => items.push({ light: T + i, bounds: areaLightBounds(l) }));
    punctualBounded.forEach((l, i) => items.push({ light: T + A + i, bounds: punctualLightBounds(l)! }));
    tree = buildLightTree(items, boundedCount);
  }
  const alias = probabilities.bounded > 0 ? buildAliasTable(boundedPower) : null;

  // Heap layout (cells).
  const cells = { selection: 0, triangles: 0, area: 0, punctual: 0, tree: 0, table: 0, portals: 0, portalData: 0, end: 0 };
  let at = 0;
  const place = (key: keyof typeof cells, count: number): void => {
    cells[key] = at;
    at += count;
  };
  const portalPack = portalsUsed ? packPortals(buildPortalEnvironmentSampler(sampler!, config.portals, { mode: config.portalMode })) : null;
  place('selection', boundedCount * (lightSelectionEntryLayout.size / 16));
  place('triangles', T * (lightRecordLayout.size / 16));
  place('area', A * (areaLightLayout.size / 16));
  place('punctual', (P + directional.length) * (punctualLightLayout.size / 16));
  place('tree', (tree?.nodes.length ?? 0) * (lightTreeNodeLayout.size / 16));
  place('table', mapUsable ? (sampler!.tableHeight + sampler!.tableWidth * sampler!.tableHeight) * (environmentTableEntryLayout.size / 16) : 0);
  place('portals', portalPack ? config.portals.length * (environmentPortalLayout.size / 16) : 0);
  place('portalData', portalPack ? Math.ceil(portalPack.data.length / 4) : 0);
  cells.end = at;

  const heap = new ArrayBuffer(Math.max(1, at) * 16);
  const bytes = new Uint8Array(heap);
  const u32 = new Uint32Array(heap);
  const f32 = new Float32Array(heap);
  const view = new DataView(heap);
  for (let g = 0; g < boundedCount; g++) {
    writeStruct(lightSelectionEntryLayout, view, cells.selection + g, {
      aliasThreshold: alias ? alias.threshold[g]! : 1,
      aliasIndex: alias ? alias.alias[g]! : g,
      pmf: alias ? alias.pmf[g]! : 0,
      treeLeaf: tree && tree.lightToLeaf[g] !== LIGHT_TREE_NONE ? tree.lightToLeaf[g]! : INDEX_NONE,
    });
  }
  bytes.set(new Uint8Array(input.triangles.records, 0, T * lightRecordLayout.size), cells.triangles * 16);
  if (A > 0) bytes.set(new Uint8Array(packAreaLights(config.area)), cells.area * 16);
  if (P + directional.length > 0) bytes.set(new Uint8Array(packPunctualLights([...punctualBounded, ...directional])), cells.punctual * 16);
  if (tree && tree.nodes.length > 0) bytes.set(new Uint8Array(packLightTree(tree)), cells.tree * 16);
  if (mapUsable) {
    const src = sampler!.entriesU32;
    const n = src.length / 3;
    for (let k = 0; k < n; k++) {
      const c = 4 * (cells.table + k);
      u32[c] = src[3 * k]!;
      u32[c + 1] = src[3 * k + 1]!;
      u32[c + 2] = src[3 * k + 2]!;
    }
  }
  if (portalPack) {
    bytes.set(new Uint8Array(portalPack.records), cells.portals * 16);
    f32.set(portalPack.data, cells.portalData * 4);
  }

  const uniforms = new ArrayBuffer(lightingUniformsLayout.size);
  writeStruct(lightingUniformsLayout, new DataView(uniforms), 0, {
    environmentMapSize: environmentMap && mapUsable ? [environmentMap.width, environmentMap.height] : [1, 1],
    environmentTableSize: mapUsable ? [sampler!.tableWidth, sampler!.tableHeight] : [1, 1],
    environmentIntensity: environmentMap && mapUsable ? environmentMap.intensity : 0,
    environmentRotationTurns: environmentMap && mapUsable ? environmentMap.rotationRadians / (2 * Math.PI) : 0,
    environmentTableOffset: cells.table,
    portalCount: portalPack ? config.portals.length : 0,
    sunDirection: sun ? sun.direction : [0, 1, 0],
    sunOneMinusCosThetaMax: sun ? sun.oneMinusCosThetaMax : 0,
    sunRadiance: sun ? sun.radiance : [0, 0, 0],
    sunLimbDarkening: sun?.limbDarkening ? 1 : 0,
    sunSelectProbability: probabilities.sun,
    directionalSelectProbability: probabilities.directional,
    boundedSelectProbability: probabilities.bounded,
    portalGuideProbability: PORTAL_GUIDE_PROBABILITY,
    selectionOffset: cells.selection,
    triangleOffset: cells.triangles,
    areaOffset: cells.area,
    punctualOffset: cells.punctual,
    treeOffset: cells.tree,
    triangleCount: T,
    areaCount: A,
    punctualCount: P,
    directionalCount: directional.length,
    boundedCount: probabilities.bounded > 0 ? boundedCount : 0,
    portalOffset: cells.portals,
    portalDataOffset: cells.portalData * 4,
    portalMode: config.portalMode === 'guide-and-gate' ? PORTAL_MODE_GUIDE_AND_GATE : PORTAL_MODE_GUIDE,
    treeNodeCount: tree?.nodes.length ?? 0,
    environmentMapEnabled: mapUsable ? 1 : 0,
  });

  return {
    heap,
    uniforms,
    environmentSelectProbability: probabilities.environment,
    uniformEnvironment,
    boundedCount,
    directionalCount: directional.length,
    environmentMap: mapUsable ? environmentMap : null,
    environmentSampler: mapUsable ? sampler : null,
    tree,
    probabilities,
    uses: {
      environment: probabilities.environment > 0,
      environmentMap: mapUsable,
      sun: probabilities.sun > 0,
      portals: portalPack !== null,
      punctualLights: P + directional.length > 0,
      areaLights: A > 0,
      lightTree: tree !== null && tree.nodes.length > 0,
    },
  };
}
