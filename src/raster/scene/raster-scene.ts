/**
 * Validation of the raster renderer's scene into the shared representation (normalizeWavefrontScene:
 * meshes, instances, core materials, textures) plus what only the raster renderer has: extension
 * factors of materials, deformable (skinned and morphed) meshes and their instances, and lights.
 */
import { describe, fail, isArrayLike, requireInteger } from '../../errors/validate.ts';
import { validatePunctualLight, type PunctualLight } from '../../lighting/punctual-lights.ts';
import { affineFromColumnMajor, identityTransform } from '../../scene/instance.ts';
import { normalizeWavefrontMesh, type NormalizedMesh } from '../../scene/mesh.ts';
import { normalizeWavefrontScene, type NormalizedScene } from '../../scene/normalize-scene.ts';
import type { WavefrontMaterialInput, WavefrontMeshInput } from '../../scene/types.ts';
import type { RasterRendererOptions, RasterSkinnedInstanceInput, RasterSkinnedMeshInput } from '../types.ts';
import { coreMaterialInput, normalizeRasterMaterial, type RasterMaterial } from './raster-material.ts';

export interface RasterSkinnedMesh {
  readonly mesh: NormalizedMesh;
  readonly influences: 0 | 4 | 8;
  readonly joints: Uint32Array | null;
  readonly weights: Float32Array | null;
  readonly jointCount: number;
  /** Per target: 9 floats per vertex laid out as positions (3n), normals (3n), tangents (3n). */
  readonly targets: Float32Array[];
  readonly material: number;
}

export interface RasterScene {
  readonly base: NormalizedScene;
  /** Aligned with base.materials, then the inline materials of skinned meshes. */
  readonly materials: RasterMaterial[];
  /** Column-major transforms of base.instances. */
  readonly instanceTransforms: Float64Array[];
  readonly skinnedMeshes: RasterSkinnedMesh[];
  readonly skinnedInstances: { mesh: number; transform: Float64Array }[];
  readonly lights: PunctualLight[];
}

/** A column-major 4x4 validated like an instance transform (affine, finite, invertible). */
export function validateTransform(value: ArrayLike<number> | undefined, field: string): Float64Array {
  const m = value ?? identityTransform;
  affineFromColumnMajor(m, field);
  return Float64Array.from(m);
}

function validateSkinnedMesh(input: RasterSkinnedMeshInput, i: number, textureCount: number, sceneMaterialCount: number, materials: RasterMaterial[]): RasterSkinnedMesh {
  const field = `skinnedMeshes[${i}]`;
  if (typeof input !== 'object' || input === null) fail('INVALID_MESH', field, `expected a mesh object, got ${describe(input)}`);
  const { influences, joints, weights, jointCount, targets, material, ...streams } = input;
  const mesh = normalizeWavefrontMesh({ ...(streams as WavefrontMeshInput), material: 0 }, i, field, { materialCount: 1, textureCount });
  const n = mesh.vertexCount;
  let materialIndex: number;
  if (typeof material === 'number') {
    materialIndex = requireInteger(material, `${field}.material`, { min: 0, max: sceneMaterialCount - 1 }, 'INVALID_MESH');
  } else {
    materials.push(normalizeRasterMaterial(material, `${field}.material`, textureCount));
    materialIndex = materials.length - 1;
  }
  if (influences !== 0 && influences !== 4 && influences !== 8) fail('INVALID_MESH', `${field}.influences`, `expected 0, 4 or 8, got ${describe(influences)}`);
  let jointArray: Uint32Array | null = null;
  let weightArray: Float32Array | null = null;
  let palette = 0;
  if (influences > 0) {
    palette = requireInteger(jointCount, `${field}.jointCount`, { min: 1, max: 65536 }, 'INVALID_MESH');
    if (!isArrayLike(joints) || joints.length !== influences * n) fail('INVALID_MESH', `${field}.joints`, `expected ${influences * n} joint indices (${influences} per vertex)`);
    if (!isArrayLike(weights) || weights.length !== influences * n) fail('INVALID_MESH', `${field}.weights`, `expected ${influences * n} weights (${influences} per vertex)`);
    jointArray = new Uint32Array(influences * n);
    weightArray = new Float32Array(influences * n);
    for (let v = 0; v < n; v++) {
      let sum = 0;
      for (let k = 0; k < influences; k++) {
        const w = weights[influences * v + k];
        if (typeof w !== 'number' || !Number.isFinite(w) || w < 0) fail('INVALID_MESH', `${field}.weights[${influences * v + k}]`, `expected a finite weight >= 0, got ${describe(w)}`);
        const j = joints[influences * v + k];
        if (typeof j !== 'number' || !Number.isInteger(j) || j < 0 || (j >= palette && w > 0)) {
          fail('INVALID_MESH', `${field}.joints[${influences * v + k}]`, `joint index ${describe(j)} is out of range for ${palette} joints`);
        }
        jointArray[influences * v + k] = j < palette ? j : 0;
        weightArray[influences * v + k] = w;
        sum += w;
      }
      if (!(sum > 0)) fail('INVALID_MESH', `${field}.weights[${influences * v}]`, 'the weights of this vertex sum to 0');
      for (let k = 0; k < influences; k++) weightArray[influences * v + k]! /= sum;
    }
  }
  const targetBlocks = (targets ?? []).map((t, k) => {
    const block = new Float32Array(9 * n);
    (['positions', 'normals', 'tangents'] as const).forEach((key, s) => {
      const values = t[key];
      if (values === undefined) return;
      if (!isArrayLike(values) || values.length !== 3 * n) fail('INVALID_MESH', `${field}.targets[${k}].${key}`, `expected ${3 * n} numbers`);
      for (let x = 0; x < 3 * n; x++) {
        const value = values[x];
        if (typeof value !== 'number' || !Number.isFinite(value)) fail('INVALID_MESH', `${field}.targets[${k}].${key}[${x}]`, `expected a finite number, got ${describe(value)}`);
        block[3 * n * s + x] = value;
      }
    });
    return block;
  });
  return { mesh, influences, joints: jointArray, weights: weightArray, jointCount: palette, targets: targetBlocks, material: materialIndex };
}

export function normalizeRasterScene(options: RasterRendererOptions): RasterScene {
  const textureCount = Array.isArray(options.textures) ? options.textures.length : 0;
  const sceneMaterials = (options.materials ?? []).map((m, i) => normalizeRasterMaterial(m, `materials[${i}]`, textureCount));
  const extensions = new Map<string, RasterMaterial>(sceneMaterials.map((m, i) => [`materials[${i}]`, m]));
  if (options.meshes !== undefined && !Array.isArray(options.meshes)) fail('INVALID_MESH', 'meshes', `expected an array, got ${describe(options.meshes)}`);
  const meshes = (options.meshes ?? []).map((mesh, i) => {
    if (typeof mesh !== 'object' || mesh === null || typeof mesh.material === 'number') return mesh;
    extensions.set(`meshes[${i}].material`, normalizeRasterMaterial(mesh.material, `meshes[${i}].material`, textureCount));
    return mesh.material === undefined ? mesh : { ...mesh, material: coreMaterialInput(mesh.material) };
  });
  const base = normalizeWavefrontScene({
    meshes,
    instances: options.instances,
    materials: (options.materials ?? []).map((m) => (typeof m === 'object' && m !== null ? coreMaterialInput(m as WavefrontMaterialInput) : m)),
    textures: options.textures,
    images: options.images,
  });
  const materials = base.materials.map((core, k) => {
    const ext = extensions.get(base.materialFields[k]!) ?? normalizeRasterMaterial(undefined, base.materialFields[k]!, textureCount);
    return { ...ext, core, textures: { ...ext.textures, ...Object.fromEntries(Object.entries(core).filter(([key]) => key.endsWith('Texture'))) } };
  });
  const instanceTransforms = base.instances.map((_, i) => Float64Array.from(options.instances?.[i]?.transform ?? identityTransform));
  if (options.skinnedMeshes !== undefined && !Array.isArray(options.skinnedMeshes)) fail('INVALID_MESH', 'skinnedMeshes', 'expected an array');
  const skinnedMeshes = (options.skinnedMeshes ?? []).map((m, i) => validateSkinnedMesh(m, i, textureCount, sceneMaterials.length, materials));
  if (options.skinnedInstances !== undefined && !Array.isArray(options.skinnedInstances)) fail('INVALID_INSTANCE', 'skinnedInstances', 'expected an array');
  const skinnedInstanceInputs: RasterSkinnedInstanceInput[] = options.skinnedInstances ?? skinnedMeshes.map((_, i) => ({ mesh: i }));
  const skinnedInstances = skinnedInstanceInputs.map((inst, i) => {
    const field = `skinnedInstances[${i}]`;
    if (typeof inst !== 'object' || inst === null) fail('INVALID_INSTANCE', field, 'expected { mesh, transform? }');
    const mesh = requireInteger(inst.mesh, `${field}.mesh`, { min: 0, max: skinnedMeshes.length - 1 }, 'INVALID_INSTANCE');
    return { mesh, transform: validateTransform(inst.transform, `${field}.transform`) };
  });
  if (options.lights !== undefined && !Array.isArray(options.lights)) fail('INVALID_LIGHT', 'lights', 'expected an array');
  const lights = (options.lights ?? []).map((l, i) => validatePunctualLight(l, `lights[${i}]`));
  return { base, materials, instanceTransforms, skinnedMeshes, skinnedInstances, lights };
}
