import type { AreaLight } from './area-lights.ts';
import type { EmissiveTriangleInput } from './emissive-lights.ts';
import type { LightBounds } from './light-bounds.ts';
import { buildLightTree, lightTreePmf, packLightTree, sampleLightTree, type LightTree } from './light-tree.ts';
import type { PunctualLight } from './punctual-lights.ts';
import { ONE_MINUS_EPSILON_F32 } from './environment-sampling.ts';
import { cross, length, luminance, scale, type Vec3 } from './vec3.ts';

/**
 * Light selection for next-event estimation over everything the renderer can sample:
 * - the light tree (light-tree.ts) over emissive triangles, area lights, and point and spot lights,
 *   with global light indices [0, T) triangles, [T, T + A) area lights, [T + A, T + A + P) punctual
 *   lights (index T + A + i is punctual light i; directional lights never enter the tree);
 * - "infinite" lights outside the tree: the environment map, the sun disc and directional lights,
 *   chosen uniformly, as pbrt-v4's BVHLightSampler does: with N infinite lights and a non-empty
 *   tree, each infinite light has probability 1 / (N + 1) and the tree 1 / (N + 1).
 *
 * The GPU (gpu-lighting.ts, light-sampling.wesl) uses the same global indices and tree, but picks
 * the infinite lights and the tree by estimated power rather than uniformly (any split is
 * unbiased), and the tree's leaves are found through each light's LightSelectionEntry.
 */

export type LightKind = 'triangle' | 'area' | 'punctual' | 'environment' | 'sun';

export interface LightRef {
  kind: LightKind;
  /** Index within its kind (triangle list, area lights, punctual lights); 0 for environment and sun. */
  index: number;
}

export interface LightSelection extends LightRef {
  pmf: number;
}

export interface LightSamplerInput {
  triangles?: readonly EmissiveTriangleInput[];
  areaLights?: readonly AreaLight[];
  punctualLights?: readonly PunctualLight[];
  environment?: boolean;
  sun?: boolean;
}

export interface LightSampler {
  tree: LightTree;
  /** LightTreeNode records (light-tree.ts). */
  nodes: ArrayBuffer;
  triangleCount: number;
  areaCount: number;
  punctualCount: number;
  infinite: LightRef[];
}

export function triangleLightBounds(t: EmissiveTriangleInput): LightBounds {
  const e1 = [t.v1[0]! - t.v0[0]!, t.v1[1]! - t.v0[1]!, t.v1[2]! - t.v0[2]!];
  const e2 = [t.v2[0]! - t.v0[0]!, t.v2[1]! - t.v0[1]!, t.v2[2]! - t.v0[2]!];
  const c = cross(e1, e2);
  const l = length(c);
  return {
    boundsMin: [Math.min(t.v0[0]!, t.v1[0]!, t.v2[0]!), Math.min(t.v0[1]!, t.v1[1]!, t.v2[1]!), Math.min(t.v0[2]!, t.v1[2]!, t.v2[2]!)],
    boundsMax: [Math.max(t.v0[0]!, t.v1[0]!, t.v2[0]!), Math.max(t.v0[1]!, t.v1[1]!, t.v2[1]!), Math.max(t.v0[2]!, t.v1[2]!, t.v2[2]!)],
    axis: l > 0 ? scale(c, 1 / l) : [0, 0, 1],
    cosThetaO: 1,
    cosThetaE: 0,
    phi: l > 0 ? luminance(t.emission) * t.area : 0,
    twoSided: t.doubleSided,
  };
}

export function areaLightBounds(l: AreaLight): LightBounds {
  const phiLum = luminance(l.radiance);
  if (l.type === 'sphere') {
    const r = l.radius;
    return {
      boundsMin: [l.center[0] - r, l.center[1] - r, l.center[2] - r],
      boundsMax: [l.center[0] + r, l.center[1] + r, l.center[2] + r],
      axis: [0, 0, 1],
      cosThetaO: -1,
      cosThetaE: 0,
      phi: phiLum * Math.PI * r * r,
      twoSided: false,
    };
  }
  let ext: Vec3;
  if (l.type === 'rectangle') {
    ext = [0, 1, 2].map((d) => Math.abs(l.edgeU[d]!) / 2 + Math.abs(l.edgeV[d]!) / 2) as Vec3;
  } else {
    ext = [0, 1, 2].map((d) => l.radius * Math.sqrt(Math.max(0, 1 - l.normal[d]! * l.normal[d]!))) as Vec3;
  }
  return {
    boundsMin: [l.center[0] - ext[0], l.center[1] - ext[1], l.center[2] - ext[2]],
    boundsMax: [l.center[0] + ext[0], l.center[1] + ext[1], l.center[2] + ext[2]],
    axis: l.normal,
    cosThetaO: 1,
    cosThetaE: 0,
    phi: phiLum * l.area,
    twoSided: l.twoSided,
  };
}

/** Point and spot lights (directional lights are not bounded: null). */
export function punctualLightBounds(l: PunctualLight): LightBounds | null {
  if (l.type === 'directional') return null;
  const phi = luminance(l.intensity);
  if (l.type === 'point') return { boundsMin: [...l.position], boundsMax: [...l.position], axis: [0, 0, 1], cosThetaO: -1, cosThetaE: 0, phi, twoSided: false };
  // Full intensity inside the inner cone, falling to 0 at the outer cone (pbrt-v4 SpotLight::Bounds).
  return {
    boundsMin: [...l.position],
    boundsMax: [...l.position],
    axis: l.direction,
    cosThetaO: Math.cos(l.innerConeAngle),
    cosThetaE: Math.cos(l.outerConeAngle - l.innerConeAngle),
    phi,
    twoSided: false,
  };
}

export function buildLightSampler(input: LightSamplerInput): LightSampler {
  const triangles = input.triangles ?? [];
  const areaLights = input.areaLights ?? [];
  const punctualLights = input.punctualLights ?? [];
  const items: { light: number; bounds: LightBounds }[] = [];
  triangles.forEach((t, i) => items.push({ light: i, bounds: triangleLightBounds(t) }));
  areaLights.forEach((l, i) => items.push({ light: triangles.length + i, bounds: areaLightBounds(l) }));
  const infinite: LightRef[] = [];
  if (input.environment) infinite.push({ kind: 'environment', index: 0 });
  if (input.sun) infinite.push({ kind: 'sun', index: 0 });
  punctualLights.forEach((l, i) => {
    const b = punctualLightBounds(l);
    if (b) items.push({ light: triangles.length + areaLights.length + i, bounds: b });
    else if (luminance(l.intensity) > 0) infinite.push({ kind: 'punctual', index: i });
  });
  const tree = buildLightTree(items, triangles.length + areaLights.length + punctualLights.length);
  return { tree, nodes: packLightTree(tree), triangleCount: triangles.length, areaCount: areaLights.length, punctualCount: punctualLights.length, infinite };
}

function treeChoices(s: LightSampler): { pTree: number; pEach: number } {
  const slots = s.infinite.length + (s.tree.nodes.length > 0 ? 1 : 0);
  if (slots === 0) return { pTree: 0, pEach: 0 };
  return { pTree: s.tree.nodes.length > 0 ? 1 / slots : 0, pEach: 1 / slots };
}

function globalToRef(s: LightSampler, g: number): LightRef {
  if (g < s.triangleCount) return { kind: 'triangle', index: g };
  if (g < s.triangleCount + s.areaCount) return { kind: 'area', index: g - s.triangleCount };
  return { kind: 'punctual', index: g - s.triangleCount - s.areaCount };
}

function refToGlobal(s: LightSampler, r: LightRef): number {
  if (r.kind === 'triangle') return r.index;
  if (r.kind === 'area') return s.triangleCount + r.index;
  return s.triangleCount + s.areaCount + r.index;
}

/** Chooses a light for a shading point (p, n) with one uniform number; null when none can be chosen. */
export function sampleLight(s: LightSampler, p: readonly number[], n: readonly number[], u: number): LightSelection | null {
  const { pTree, pEach } = treeChoices(s);
  if (pEach === 0) return null;
  const slots = s.infinite.length + (pTree > 0 ? 1 : 0);
  const scaled = u * slots;
  const slot = Math.min(Math.floor(scaled), slots - 1);
  if (slot < s.infinite.length) return { ...s.infinite[slot]!, pmf: pEach };
  const t = sampleLightTree(s.tree, p, n, Math.min(scaled - slot, ONE_MINUS_EPSILON_F32));
  return t ? { ...globalToRef(s, t.light), pmf: pTree * t.pmf } : null;
}

/** Probability that `sampleLight` chooses `light` at (p, n): the light-selection factor of MIS weights. */
export function lightPmf(s: LightSampler, p: readonly number[], n: readonly number[], light: LightRef): number {
  const { pTree, pEach } = treeChoices(s);
  if (light.kind === 'environment' || light.kind === 'sun' || (light.kind === 'punctual' && s.infinite.some((r) => r.kind === 'punctual' && r.index === light.index))) {
    return s.infinite.some((r) => r.kind === light.kind && r.index === light.index) ? pEach : 0;
  }
  return pTree * lightTreePmf(s.tree, p, n, refToGlobal(s, light));
}
