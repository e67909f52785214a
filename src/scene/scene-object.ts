import { fail, requireNumberInRange, requireVec } from '../errors/validate.ts';
import { maxRadiance } from './limits.ts';
import type { NormalizedMaterial } from './material.ts';
import type { WavefrontSceneObjectInput } from './types.ts';

/**
 * `materialKind`: which debug material the object is, checked against its fields and setting the
 * defaults they leave open. 'diffuse': a dielectric base (metallic 0); 'metal': a conductor
 * (metallic 1); 'emissive': an emitter (needs `emission` with radiance > 0). Without a kind every
 * field keeps its own default.
 */
export const sceneObjectMaterialKinds = ['diffuse', 'metal', 'emissive'] as const;
export type SceneObjectMaterialKind = (typeof sceneObjectMaterialKinds)[number];

/** The metallic factor: the field if given (it must agree with the kind), else the kind's. */
function metallicOf(input: WavefrontSceneObjectInput, field: string, code: 'INVALID_SCENE_OBJECT'): number {
  const kind = input.materialKind;
  if (kind !== undefined && !sceneObjectMaterialKinds.includes(kind)) {
    fail(code, `${field}.materialKind`, `expected one of ${sceneObjectMaterialKinds.join(', ')}, got ${JSON.stringify(kind)}`);
  }
  const pinned = kind === 'metal' ? 1 : kind === 'diffuse' ? 0 : undefined;
  if (input.metallic === undefined) return pinned ?? 0;
  const metallic = requireNumberInRange(input.metallic, `${field}.metallic`, { min: 0, max: 1 }, code);
  if (pinned !== undefined && metallic !== pinned) fail(code, `${field}.metallic`, `is ${metallic}, but materialKind '${kind}' means metallic ${pinned}`);
  return metallic;
}

/** An analytic debug fixture: a sphere or an axis-aligned box with its own material. */
export interface NormalizedSceneObject {
  type: 'sphere' | 'box';
  /** Sphere centre or box minimum. */
  a: [number, number, number];
  /** [radius, 0, 0] for spheres, box maximum for boxes. */
  b: [number, number, number];
  material: NormalizedMaterial;
}

export function normalizeWavefrontSceneObject(input: WavefrontSceneObjectInput, index = 0): NormalizedSceneObject {
  const field = `sceneObjects[${index}]`;
  if (typeof input !== 'object' || input === null) fail('INVALID_SCENE_OBJECT', field, 'expected an object');
  const code = 'INVALID_SCENE_OBJECT';
  const colorIn = input.color === undefined ? [0.8, 0.8, 0.8] : requireVec(input.color, 3, `${field}.color`, code);
  colorIn.forEach((c, i) => requireNumberInRange(c, `${field}.color[${i}]`, { min: 0 }, code));
  let emission: [number, number, number] = [0, 0, 0];
  if (input.emission !== undefined) {
    const e = requireVec(input.emission, 4, `${field}.emission`, code);
    e.forEach((c, i) => requireNumberInRange(c, `${field}.emission[${i}]`, { min: 0 }, code));
    emission = [e[0]! * e[3]!, e[1]! * e[3]!, e[2]! * e[3]!];
    emission.forEach((c, i) => {
      if (!(c <= maxRadiance)) fail(code, `${field}.emission`, `emitted radiance ${c} in channel ${i} exceeds the supported maximum ${maxRadiance}`);
    });
  }
  const metallic = metallicOf(input, field, code);
  if (input.materialKind === 'emissive' && !emission.some((c) => c > 0)) fail(code, `${field}.emission`, "materialKind 'emissive' needs emission with radiance > 0");
  const material: NormalizedMaterial = {
    baseColor: [colorIn[0]!, colorIn[1]!, colorIn[2]!, 1],
    emission,
    metallic,
    roughness: input.roughness === undefined ? 1 : requireNumberInRange(input.roughness, `${field}.roughness`, { min: 0, max: 1 }, code),
    ior: input.ior === undefined ? 1.5 : requireNumberInRange(input.ior, `${field}.ior`, { min: 1, max: 10 }, code),
    doubleSided: true,
    alphaMode: 'OPAQUE',
    alphaCutoff: 0.5,
  };
  if (input.type === 'sphere') {
    const center = requireVec(input.center, 3, `${field}.center`, code) as [number, number, number];
    const radius = requireNumberInRange(input.radius, `${field}.radius`, { min: Number.MIN_VALUE }, code);
    return { type: 'sphere', a: center, b: [radius, 0, 0], material };
  }
  if (input.type === 'box') {
    const min = requireVec(input.min, 3, `${field}.min`, code) as [number, number, number];
    const max = requireVec(input.max, 3, `${field}.max`, code) as [number, number, number];
    for (let i = 0; i < 3; i++) if (!(max[i]! > min[i]!)) fail(code, `${field}.max[${i}]`, 'box max must exceed min on every axis');
    return { type: 'box', a: min, b: max, material };
  }
  return fail(code, `${field}.type`, `expected "sphere" or "box", got ${JSON.stringify((input as { type?: unknown }).type)}`);
}

