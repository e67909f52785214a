/**
 * Scene JSON files with their external resources: images given by `uri` (relative to the file, an
 * absolute URL, or a data URI; PNG, JPEG or WebP) are decoded, and `gltf` references are loaded and
 * merged (see gltf/scene-file-references.ts). Errors are INVALID_SCENE_FILE naming the field, except
 * the glTF loader's own, which keep their code and JSON pointer.
 */
import { GpuRendererError, isGpuRendererError } from '../errors/gpu-renderer-error.ts';
import { parseSceneFile, type WavefrontSceneFile } from '../scene/scene-file.ts';
import type { WavefrontImageInput, WavefrontSceneDescription } from '../scene/types.ts';
import type { EnvironmentMapInput } from '../lighting/environment-map.ts';
import { loadEnvironmentMap, type NegativeTexelReport } from '../lighting/load-environment-map.ts';
import { decodeImage } from './gltf/image-decoding.ts';
import { readResource, readUrl, sourceStringToUrl } from './gltf/resources.ts';
import { resolveGltfReferences } from './gltf/scene-file-references.ts';

/** A resolved scene: the description plus, when its environment names a map file, that map. */
export type WavefrontResolvedScene = WavefrontSceneDescription & { environmentMap?: EnvironmentMapInput };

export interface ResolvedSceneFile {
  scene: WavefrontResolvedScene;
  /** Notes from decoding and loading (e.g. glTF loader warnings), for the user. */
  warnings: string[];
}

function asSceneFileError(error: unknown, field: string): GpuRendererError {
  if (!isGpuRendererError(error)) return new GpuRendererError('INVALID_SCENE_FILE', String(error), { field, cause: error });
  const message = error.field ? error.message.slice(error.field.length + 2) : error.message;
  return new GpuRendererError('INVALID_SCENE_FILE', message, { field, cause: error });
}

export interface ResolveSceneFileOptions {
  /** Locates relative URIs (loadSceneFile: the file itself). */
  base?: string | URL;
  signal?: AbortSignal;
  /**
   * What to do with negative texels of an environment map file whose `environment` does not say
   * (`negativeTexels` there wins): 'error' (default) or 'zero'; see loadEnvironmentMap.
   */
  negativeTexels?: 'error' | 'zero';
  /** Called with what zeroing negative texels changed (also when nothing was), and the field. */
  onNegativeTexels?: (report: NegativeTexelReport, field: string) => void;
}

/** Decodes `uri` images and loads `gltf` references of a parsed scene file; `base` locates relative URIs. */
export async function resolveSceneFile(file: WavefrontSceneFile, options: ResolveSceneFileOptions = {}): Promise<ResolvedSceneFile> {
  const base = options.base === undefined ? undefined : options.base instanceof URL ? options.base : await sourceStringToUrl(options.base);
  const warnings: string[] = [];
  const { gltf, images, environment, ...rest } = file;
  const scene: WavefrontResolvedScene = { ...rest };
  if (environment !== undefined && 'map' in environment) {
    // An environment map file (.hdr or .exr) becomes the renderer's environmentMap option.
    const field = 'environment.map';
    try {
      const bytes = await readResource(environment.map, base, field, options.signal);
      const onNegativeTexels = options.onNegativeTexels;
      scene.environmentMap = await loadEnvironmentMap(bytes, {
        field,
        negativeTexels: environment.negativeTexels ?? options.negativeTexels ?? 'error',
        ...(onNegativeTexels ? { onNegativeTexels: (report: NegativeTexelReport) => onNegativeTexels(report, field) } : {}),
        ...(environment.intensity !== undefined ? { intensity: environment.intensity } : {}),
        ...(environment.rotationDegrees !== undefined ? { rotationRadians: (environment.rotationDegrees * Math.PI) / 180 } : {}),
      });
    } catch (error) {
      throw asSceneFileError(error, field);
    }
  } else if (environment !== undefined) {
    scene.environment = environment;
  }
  if (images !== undefined) {
    scene.images = await Promise.all(
      images.map(async (image, i): Promise<WavefrontImageInput> => {
        if (!('uri' in image)) return image;
        const field = `images[${i}].uri`;
        try {
          const decoded = await decodeImage(await readResource(image.uri, base, field, options.signal), field);
          for (const note of decoded.notes) warnings.push(`${field}: ${note}`);
          return decoded.image;
        } catch (error) {
          throw asSceneFileError(error, field);
        }
      }),
    );
  }
  if (gltf === undefined || gltf.length === 0) return { scene, warnings };
  const merged = await resolveGltfReferences(scene, gltf, { ...(base ? { base } : {}), ...(options.signal ? { signal: options.signal } : {}) });
  return { scene: merged.scene, warnings: [...warnings, ...merged.warnings] };
}

/** Reads, parses and resolves a scene JSON file (Node: a path; anywhere: a URL). */
export async function loadSceneFile(source: string | URL, options: Omit<ResolveSceneFileOptions, 'base'> = {}): Promise<ResolvedSceneFile> {
  const url = source instanceof URL ? source : await sourceStringToUrl(source);
  let text: string;
  try {
    text = new TextDecoder().decode(await readUrl(url, options.signal));
  } catch (error) {
    throw new GpuRendererError('INVALID_SCENE_FILE', `cannot read ${url.href}: ${(error as Error).message}`, { field: 'scene', cause: error });
  }
  return resolveSceneFile(parseSceneFile(text, String(source)), { base: url, ...options });
}
