/**
 * Appends a loaded glTF scene (its meshes, materials, textures and images) to a scene under
 * construction, re-indexing material and texture references, and places its instances under a
 * parent transform.
 */
import { mat4d } from 'wgpu-matrix';
import type { GltfScene } from '../../io/gltf/load-gltf-scene.ts';
import type { WavefrontInstanceInput, WavefrontMaterialInput, WavefrontMeshInput, WavefrontSceneDescription, WavefrontTextureInput, WavefrontTextureRefInput } from '../../scene/types.ts';

export interface SceneParts {
  meshes: WavefrontMeshInput[];
  instances: WavefrontInstanceInput[];
  materials: WavefrontMaterialInput[];
  textures: WavefrontTextureInput[];
  images: NonNullable<WavefrontSceneDescription['images']>;
}

export function emptySceneParts(): SceneParts {
  return { meshes: [], instances: [], materials: [], textures: [], images: [] };
}

/** Material with every texture reference moved by `offset`. */
export function offsetMaterialTextures(material: WavefrontMaterialInput, offset: number): WavefrontMaterialInput {
  const out: Record<string, unknown> = { ...material };
  for (const [key, value] of Object.entries(material)) {
    if (key.endsWith('Texture') && typeof value === 'object' && value !== null) out[key] = { ...(value as WavefrontTextureRefInput), index: (value as WavefrontTextureRefInput).index + offset };
  }
  return out as WavefrontMaterialInput;
}

/** Appends the glTF scene's materials, textures and images; returns the material index offset. */
export function appendMaterials(parts: SceneParts, scene: Pick<GltfScene, 'materials' | 'textures' | 'images'>): number {
  const imageOffset = parts.images.length;
  const textureOffset = parts.textures.length;
  const materialOffset = parts.materials.length;
  parts.images.push(...scene.images);
  parts.textures.push(...scene.textures.map((t) => ({ ...t, image: typeof t.image === 'number' ? t.image + imageOffset : t.image })));
  parts.materials.push(...scene.materials.map((m) => offsetMaterialTextures(m, textureOffset)));
  return materialOffset;
}

/** Appends a whole glTF scene placed by `parent`; returns the indices of the instances added. */
export function appendGltfScene(parts: SceneParts, scene: GltfScene, parent: ArrayLike<number>): number[] {
  const materialOffset = appendMaterials(parts, scene);
  const meshOffset = parts.meshes.length;
  for (const mesh of scene.meshes) parts.meshes.push({ ...mesh, material: typeof mesh.material === 'number' ? mesh.material + materialOffset : mesh.material });
  const added: number[] = [];
  for (const inst of scene.instances) {
    added.push(parts.instances.length);
    parts.instances.push({ mesh: inst.mesh + meshOffset, transform: Array.from(mat4d.multiply(parent, inst.transform ?? mat4d.identity())), ...(inst.material !== undefined ? { material: inst.material + materialOffset } : {}) });
  }
  return added;
}
