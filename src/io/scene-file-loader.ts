/**
 * Scene JSON files with their external resources: images given by `uri` (relative to the file and
 * inside its folder, a URL of an allowed origin, or a data URI; PNG, JPEG or WebP) are decoded, and
 * `gltf` references are loaded and merged (see gltf/scene-file-references.ts), all under one
 * resource policy and budget (resource-policy.ts). Errors are INVALID_SCENE_FILE naming the field,
 * except the glTF loader's own, which keep their code and JSON pointer.
 */
import { GpuRendererError, isGpuRendererError } from '../errors/gpu-renderer-error.ts';
import { parseSceneFile, type WavefrontSceneFile } from '../scene/scene-file.ts';
import type { WavefrontImageInput, WavefrontSceneDescription } from '../scene/types.ts';
import type { EnvironmentMapInput } from '../lighting/environment-map.ts';
import { loadEnvironmentMap, type NegativeTexelReport } from '../lighting/load-environment-map.ts';
import { validateLightingOptions } from '../lighting/lighting-options.ts';
import { requireNumberInRange } from '../errors/validate.ts';
import { maxRadiance } from '../scene/limits.ts';
import { normalizeWavefrontCamera } from '../pathtracer/camera.ts';
import { normalizeWavefrontScene } from '../scene/normalize-scene.ts';
import { validateTextures } from '../materials/textures/texture-input.ts';
import { decodeImage } from './gltf/image-decoding.ts';
import { resolveGltfReferences } from './gltf/scene-file-references.ts';
import { checkImageHeader } from './image-headers.ts';
import { JSON_BYTES_PER_VALUE, MAX_JSON_DEPTH, scanJson } from './json-scan.ts';
import { budgetOf, derivePolicy, locateSource, readByteSource, readReference, resolveResourcePolicy, type ResourcePolicy } from './resource-policy.ts';

/** A resolved scene: the description plus, when its environment names a map file, that map. */
export type WavefrontResolvedScene = WavefrontSceneDescription & { environmentMap?: EnvironmentMapInput };

export interface ResolvedSceneFile {
  scene: WavefrontResolvedScene;
  /** Notes from decoding and loading (e.g. glTF loader warnings), for the user. */
  warnings: string[];
}

/** Options of `resolveSceneFile` (and, but for `base`, of `loadSceneFile`). */
export interface ResolveSceneFileOptions {
  /** Locates relative URIs (loadSceneFile: the file itself); references must stay in its folder. */
  base?: string | URL;
  /** Ends reading and fetching; the load rejects with the signal's reason. */
  signal?: AbortSignal;
  /**
   * What to do with negative texels of an environment map file whose `environment` does not say
   * (`negativeTexels` there wins): 'error' (default) or 'zero'; see loadEnvironmentMap.
   */
  negativeTexels?: 'error' | 'zero';
  /** Called with what zeroing negative texels changed (also when nothing was), and the field. */
  onNegativeTexels?: (report: NegativeTexelReport, field: string) => void;
  /** What the file's references may read and how much the load may decode (resource-policy.ts). */
  resourcePolicy?: ResourcePolicy;
}

function asSceneFileError(error: unknown, field: string): GpuRendererError {
  if (!isGpuRendererError(error)) return new GpuRendererError('INVALID_SCENE_FILE', String(error), { field, cause: error });
  const message = error.field ? error.message.slice(error.field.length + 2) : error.message;
  return new GpuRendererError('INVALID_SCENE_FILE', message, { field, cause: error });
}

/**
 * Decodes `uri` images and loads `gltf` references of a parsed scene file; `base` (the file's path
 * or URL) locates relative URIs, which must stay in its folder. Without `base` only data URIs can
 * be referenced.
 */
export async function resolveSceneFile(file: WavefrontSceneFile, options: ResolveSceneFileOptions = {}): Promise<ResolvedSceneFile> {
  const base = options.base === undefined ? undefined : await locateSource(options.base, { code: 'INVALID_OPTION', field: 'base' });
  const resolved = await resolveResourcePolicy(options.resourcePolicy);
  const policy = resolved.budget === undefined ? derivePolicy(resolved, { budget: budgetOf(resolved) }) : resolved;
  const { signal } = options;
  const warnings: string[] = [];
  const { gltf, images, environment, ...rest } = file;
  const scene: WavefrontResolvedScene = { ...rest };
  if (environment !== undefined && 'map' in environment) {
    // An environment map file (.hdr or .exr) becomes the renderer's environmentMap option.
    const field = 'environment.map';
    try {
      const bytes = await readReference(environment.map, base, policy, { code: 'INVALID_SCENE_FILE', field }, signal);
      const onNegativeTexels = options.onNegativeTexels;
      scene.environmentMap = await loadEnvironmentMap(bytes, {
        field,
        resourcePolicy: policy,
        negativeTexels: environment.negativeTexels ?? options.negativeTexels ?? 'error',
        ...(onNegativeTexels ? { onNegativeTexels: (report: NegativeTexelReport) => onNegativeTexels(report, field) } : {}),
        ...(environment.intensity !== undefined ? { intensity: environment.intensity } : {}),
        ...(environment.rotationDegrees !== undefined ? { rotationRadians: (environment.rotationDegrees * Math.PI) / 180 } : {}),
      });
    } catch (error) {
      // The map's own options are the file's intensity and rotationDegrees.
      const inner = isGpuRendererError(error) ? (error.field ?? '') : '';
      throw asSceneFileError(error, inner.endsWith('.intensity') ? 'environment.intensity' : inner.endsWith('.rotationRadians') ? 'environment.rotationDegrees' : field);
    }
  } else if (environment !== undefined) {
    scene.environment = environment;
  }
  if (images !== undefined) {
    scene.images = await Promise.all(
      images.map(async (image, i): Promise<WavefrontImageInput> => {
        if (!('uri' in image)) return image;
        const field = `images[${i}].uri`;
        const site = { code: 'INVALID_SCENE_FILE', field } as const;
        try {
          const bytes = await readReference(image.uri, base, policy, site, signal);
          checkImageHeader(bytes, site, policy, policy.budget);
          const decoded = await decodeImage(bytes, field, policy);
          for (const note of decoded.notes) warnings.push(`${field}: ${note}`);
          return decoded.image;
        } catch (error) {
          throw asSceneFileError(error, field);
        }
      }),
    );
  }
  if (gltf === undefined || gltf.length === 0) {
    acceptSceneFile(scene);
    return { scene, warnings };
  }
  // The file's own content first (its fields are the file's), then the merge.
  acceptSceneFile(scene);
  const merged = await resolveGltfReferences(scene, gltf, { ...(base ? { base } : {}), ...(signal ? { signal } : {}), resourcePolicy: policy });
  return { scene: merged.scene, warnings: [...warnings, ...merged.warnings] };
}

/**
 * The scene through the renderer's own validation (scene parts, lights, camera), so that a file
 * the renderer would refuse is refused at load, as INVALID_SCENE_FILE naming the same field.
 */
function acceptSceneFile(scene: WavefrontResolvedScene): void {
  try {
    normalizeWavefrontScene(scene);
    validateTextures(scene.textures, scene.images);
    validateLightingOptions({ lights: scene.lights }, [0, 0, 0]);
    if (scene.camera !== undefined) normalizeWavefrontCamera(scene.camera);
    scene.environment?.color.forEach((c, i) => requireNumberInRange(c, `environment.color[${i}]`, { min: 0, max: maxRadiance }));
  } catch (error) {
    if (!isGpuRendererError(error)) throw error;
    throw new GpuRendererError('INVALID_SCENE_FILE', error.field && error.message.startsWith(`${error.field}: `) ? error.message.slice(error.field.length + 2) : error.message, {
      ...(error.field !== undefined ? { field: error.field } : {}),
      cause: error,
    });
  }
}

/** Reads, parses and resolves a scene JSON file (Node: a path; anywhere: a URL). */
export async function loadSceneFile(source: string | URL, options: Omit<ResolveSceneFileOptions, 'base'> = {}): Promise<ResolvedSceneFile> {
  const site = { code: 'INVALID_SCENE_FILE', field: 'scene' } as const;
  if (typeof source !== 'string' && !(source instanceof URL)) throw new GpuRendererError('INVALID_OPTION', `expected a path or a URL, got ${source === null ? 'null' : typeof source}`, { field: 'source' });
  const resolved = await resolveResourcePolicy(options.resourcePolicy);
  const policy = derivePolicy(resolved, { budget: budgetOf(resolved) });
  const { bytes, url } = await readByteSource(source, policy, site, options.signal);
  const shape = scanJson(bytes);
  if (shape.depth > MAX_JSON_DEPTH) throw new GpuRendererError('INVALID_SCENE_FILE', `the JSON nests ${shape.depth} levels deep; the loader reads at most ${MAX_JSON_DEPTH}`, { field: 'scene' });
  policy.budget!.charge(shape.values * JSON_BYTES_PER_VALUE, site, `parsing the JSON's ${shape.values} values`);
  let text: string;
  try {
    text = new TextDecoder('utf-8', { fatal: true }).decode(bytes);
  } catch (error) {
    throw new GpuRendererError('INVALID_SCENE_FILE', `${url!.href} is not UTF-8 text`, { field: 'scene', cause: error });
  }
  return resolveSceneFile(parseSceneFile(text, String(source)), { ...options, base: url, resourcePolicy: policy });
}
