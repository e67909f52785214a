/**
 * The loaded scene through the renderer's own validation (the checks every renderer runs on its
 * scene: scene/normalize-scene.ts, lighting/lighting-options.ts, pathtracer/camera.ts) before it is returned,
 * so that a glTF the renderer would refuse is refused here, at load, as INVALID_GLTF at the JSON
 * pointer of what it came from, instead of later under the renderer's own field names
 * (`meshes[14].colors[3]`). The JSON-level checks catch most faults with a narrower pointer first;
 * this pass holds the rest (vertex colours out of [0, 1], coordinates beyond the renderer's range,
 * near-singular instance transforms, and whatever the renderer checks in the future).
 */
import { isGpuRendererError } from '../../errors/gpu-renderer-error.ts';
import { validateLightingOptions } from '../../lighting/lighting-options.ts';
import { normalizeWavefrontCamera } from '../../pathtracer/camera.ts';
import { normalizeWavefrontScene } from '../../scene/normalize-scene.ts';
import type { WavefrontCameraInput, WavefrontSceneDescription } from '../../scene/types.ts';
import { gltfError } from './errors.ts';

/** JSON pointers of what each scene entry came from, by entry index. */
export interface SceneOrigins {
  meshes: string[];
  materials: string[];
  instances: string[];
  lights: string[];
  images: string[];
}

/** Renderer stream names -> glTF attribute semantics. */
const STREAMS: Readonly<Record<string, string>> = {
  positions: '/attributes/POSITION',
  normals: '/attributes/NORMAL',
  tangents: '/attributes/TANGENT',
  uvs: '/attributes/TEXCOORD_0',
  uvs1: '/attributes/TEXCOORD_1',
  colors: '/attributes/COLOR_0',
  indices: '/indices',
};

function originOf(field: string, origins: SceneOrigins): string {
  const m = /^(meshes|materials|instances|images|lights)\[(\d+)\](?:\.(\w+))?/.exec(field);
  if (m === null) return '';
  const base = origins[m[1] as keyof SceneOrigins][Number(m[2])] ?? '';
  if (m[1] === 'meshes' && m[3] !== undefined && STREAMS[m[3]] !== undefined) return `${base}${STREAMS[m[3]]}`;
  return base;
}

function rethrow(error: unknown, origins: SceneOrigins): never {
  if (!isGpuRendererError(error)) throw error;
  const field = error.field ?? '';
  const message = field !== '' && error.message.startsWith(`${field}: `) ? error.message.slice(field.length + 2) : error.message;
  throw gltfError(originOf(field, origins), `the renderer cannot use it (${field}: ${message})`, error);
}

/** Throws INVALID_GLTF at the origin of the first entry the renderer would refuse. */
export function acceptScene(
  scene: Pick<WavefrontSceneDescription, 'meshes' | 'instances' | 'materials' | 'textures' | 'images' | 'lights'>,
  origins: SceneOrigins,
  cameras: ReadonlyArray<{ camera: WavefrontCameraInput; at: string }>,
): void {
  try {
    normalizeWavefrontScene(scene);
    // The lights as the renderer's lighting options take them (types, ranges, magnitudes).
    validateLightingOptions({ lights: scene.lights }, [0, 0, 0]);
  } catch (error) {
    rethrow(error, origins);
  }
  for (const { camera, at } of cameras) {
    try {
      normalizeWavefrontCamera(camera);
    } catch (error) {
      if (!isGpuRendererError(error)) throw error;
      throw gltfError(at, `the renderer cannot use this camera (${error.message})`, error);
    }
  }
}
