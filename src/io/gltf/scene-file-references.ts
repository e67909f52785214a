/**
 * glTF assets referenced from a scene JSON file: src/scene/gltf-references.ts checks the `gltf`
 * value, this module loads and merges the assets it names:
 *
 * ```json
 * {
 *   "gltf": [
 *     { "src": "models/room.glb", "camera": "Camera", "variant": "Night" },
 *     { "src": "models/chair.glb", "transform": [1,0,0,0, 0,1,0,0, 0,0,1,0, 2,0,-1,1] }
 *   ],
 *   "environment": { "color": [0.1, 0.1, 0.1] }
 * }
 * ```
 *
 * `gltf` is one reference or an array; a reference is a string (`"model.glb"`) or an object with
 * `src` (resolved against the scene file's location), and optional `camera` (index or name),
 * `variant`, `scene` (index or name), `animation` (index or name, null for none) with `time`
 * (seconds: the pose, as `loadGltfScene` takes them) and `transform` (column-major 4x4 placing the
 * whole asset).
 * The assets are merged after the file's own content: their meshes, materials, textures and images
 * are appended with indices offset, their instances and lights placed by `transform`. The file's
 * `camera` wins; otherwise the first reference's camera is used (its chosen or default camera).
 */
import { GpuRendererError, isGpuRendererError } from '../../errors/gpu-renderer-error.ts';
import { validateLightingOptions } from '../../lighting/lighting-options.ts';
import { normalizeWavefrontCamera } from '../../pathtracer/camera.ts';
import { affineFromColumnMajor } from '../../scene/instance.ts';
import type { GltfSceneReference } from '../../scene/gltf-references.ts';
import type { WavefrontMaterialInput, WavefrontPunctualLightInput, WavefrontSceneDescription } from '../../scene/types.ts';
import { loadGltfScene, type GltfLoadOptions, type GltfScene } from './load-gltf-scene.ts';
import { IDENTITY, multiply, normalize, transformDirection, transformPoint } from '../../math/mat4.ts';
import { budgetOf, derivePolicy, folderOf, isInsideFolder, locateSource, resolveReference, resolveResourcePolicy, type ResourcePolicy } from '../resource-policy.ts';

function invalid(field: string, message: string): never {
  throw new GpuRendererError('INVALID_SCENE_FILE', message, { field });
}

function placeLight(light: WavefrontPunctualLightInput, m: readonly number[]): WavefrontPunctualLightInput {
  const out = { ...light };
  if (light.position !== undefined) out.position = transformPoint(m, light.position);
  if (light.direction !== undefined) out.direction = normalize(transformDirection(m, light.direction));
  return out;
}

/**
 * Loads every reference (relative to `base`, the scene file's path or URL, and inside its folder
 * under `resourcePolicy`: see src/io/resource-policy.ts) and merges it into `scene`. Returns the
 * merged scene and the loaders' warnings, each prefixed with its reference. Loader errors keep
 * their code and JSON pointer; the message names the reference. Without `base` only data URIs
 * can be referenced.
 */
export async function resolveGltfReferences(
  scene: WavefrontSceneDescription,
  references: readonly GltfSceneReference[],
  options: { base?: string | URL; signal?: AbortSignal; resourcePolicy?: ResourcePolicy; load?: (source: URL, options: GltfLoadOptions) => Promise<GltfScene> } = {},
): Promise<{ scene: WavefrontSceneDescription; warnings: string[] }> {
  const load = options.load ?? loadGltfScene;
  const baseUrl = options.base === undefined ? undefined : await locateSource(options.base, { code: 'INVALID_OPTION', field: 'base' });
  const resolved = await resolveResourcePolicy(options.resourcePolicy);
  // The assets share one budget: references cannot multiply what a scene file may decode.
  const policy = derivePolicy(resolved, { budget: budgetOf(resolved) });
  const folder = baseUrl === undefined ? undefined : folderOf(baseUrl);
  const out: WavefrontSceneDescription = {
    ...scene,
    meshes: [...(scene.meshes ?? [])],
    materials: [...(scene.materials ?? [])],
    textures: [...(scene.textures ?? [])],
    images: [...(scene.images ?? [])],
    lights: [...(scene.lights ?? [])],
  };
  // With instances present only instances are drawn: the file's own meshes get identity placements.
  out.instances = scene.instances !== undefined ? [...scene.instances] : out.meshes!.map((_, mesh) => ({ mesh }));
  const warnings: string[] = [];
  for (let i = 0; i < references.length; i++) {
    const ref = references[i];
    const label = `gltf[${i}] (${JSON.stringify(ref.src)})`;
    const site = { code: 'INVALID_SCENE_FILE', field: `gltf[${i}].src` } as const;
    // A data URI carries the asset itself; anything else is a reference under the policy.
    const url = /^data:/i.test(ref.src) ? await locateSource(ref.src, site) : resolveReference(ref.src, baseUrl, policy, site);
    // The asset file itself must be a regular file inside the scene's folder (after links).
    const assetPolicy = folder !== undefined && isInsideFolder(url, folder) ? derivePolicy(policy, { root: folder }) : policy;
    let gltf: GltfScene;
    try {
      gltf = await load(url, {
        ...(ref.camera !== undefined ? { camera: ref.camera } : {}),
        ...(ref.variant !== undefined ? { variant: ref.variant } : {}),
        ...(ref.scene !== undefined ? { scene: ref.scene } : {}),
        ...(ref.animation !== undefined ? { animation: ref.animation } : {}),
        ...(ref.time !== undefined ? { time: ref.time } : {}),
        ...(options.signal !== undefined ? { signal: options.signal } : {}),
        resourcePolicy: assetPolicy,
      });
    } catch (error) {
      if (!isGpuRendererError(error)) throw error;
      const message = error.field ? error.message.slice(error.field.length + 2) : error.message;
      // A fault of the file as a whole (unreadable, not a glTF) names the reference that led to it.
      throw new GpuRendererError(error.code, `in ${label}: ${message}`, { field: error.field ? error.field : site.field, cause: error });
    }
    for (const w of gltf.warnings) warnings.push(`${label}: ${w}`);
    const m = ref.transform ?? [...IDENTITY];
    const meshOffset = out.meshes!.length;
    const materialOffset = out.materials!.length;
    const textureOffset = out.textures!.length;
    const imageOffset = out.images!.length;
    out.images!.push(...gltf.images);
    out.textures!.push(...gltf.textures.map((t) => ({ ...t, image: typeof t.image === 'number' ? t.image + imageOffset : t.image })));
    out.materials!.push(...gltf.materials.map((material) => offsetTextureRefs(material, textureOffset)));
    out.meshes!.push(...gltf.meshes.map((mesh) => ({ ...mesh, material: typeof mesh.material === 'number' ? mesh.material + materialOffset : mesh.material })));
    const placed = gltf.instances.map((inst) => ({ ...inst, mesh: inst.mesh + meshOffset, transform: multiply(m, inst.transform ?? IDENTITY), ...(inst.material === undefined ? {} : { material: inst.material + materialOffset }) }));
    const lights = gltf.lights.map((light) => placeLight(light, m));
    const camera = out.camera === undefined ? { ...gltf.camera, position: transformPoint(m, gltf.camera.position), target: transformPoint(m, gltf.camera.target), up: normalize(transformDirection(m, gltf.camera.up ?? [0, 1, 0])) } : undefined;
    checkPlacement(placed, lights, camera, `gltf[${i}].transform`);
    out.instances.push(...placed);
    out.lights!.push(...lights);
    if (camera !== undefined) out.camera = camera;
  }
  return { scene: out, warnings };
}

/**
 * The asset as `transform` places it must stay within what the renderer supports (its checks on
 * instances, lights and the camera): a fault is the reference's transform, named as such.
 */
function checkPlacement(instances: WavefrontSceneDescription['instances'] & object, lights: WavefrontPunctualLightInput[], camera: WavefrontSceneDescription['camera'], field: string): void {
  try {
    instances.forEach((inst, k) => affineFromColumnMajor(inst.transform ?? IDENTITY, `instances[${k}].transform`));
    validateLightingOptions({ lights }, [0, 0, 0]);
    if (camera !== undefined) normalizeWavefrontCamera(camera);
  } catch (error) {
    if (!isGpuRendererError(error)) throw error;
    invalid(field, `places the asset where the renderer cannot use it (${error.message})`);
  }
}

function offsetTextureRefs(material: WavefrontMaterialInput, offset: number): WavefrontMaterialInput {
  const out = { ...material } as Record<string, unknown>;
  for (const [key, value] of Object.entries(out)) {
    if (key.endsWith('Texture') && typeof value === 'object' && value !== null && 'index' in value) out[key] = { ...value, index: (value as { index: number }).index + offset };
  }
  return out as WavefrontMaterialInput;
}
