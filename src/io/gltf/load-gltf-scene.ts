// The glTF loader's public entry. Its body (gltf-scene-reader.ts, with @gltf-transform and the
// image and geometry decoders behind it) is imported on the first call, so an application that
// never loads glTF does not carry it, and bundlers put it in a chunk of its own.
import type { GltfSource } from './document-reader.ts';
import type { GltfLoadOptions, GltfScene } from './gltf-scene-reader.ts';

export type { GltfSource, GltfDecoderModules } from './document-reader.ts';
export type { GltfBounds, GltfCameraInfo } from './cameras.ts';
export type { GltfLoadOptions, GltfPoseAgainOptions, GltfScene } from './gltf-scene-reader.ts';
export type { GltfAnimationInfo, GltfPoseOptions } from './posing.ts';

/**
 * Loads a glTF 2.0 asset as a renderer scene. `source` is a file path (Node), a URL string or
 * `URL` (fetched; relative resources resolve against it), an `ArrayBuffer`/`Uint8Array` holding a
 * .glb or .gltf JSON with data URIs, or a @gltf-transform `Document`.
 *
 * Bad input throws `GpuRendererError` with code `INVALID_GLTF` and `field` a JSON pointer into the
 * asset (`/accessors/7`, `/meshes/3/primitives/0/indices`, `/images/2`, `/extensionsRequired/0`),
 * or a `glb:` path for GLB container faults (`glb:/header/magic`, `glb:/chunks/0/chunkLength`).
 * Nothing is returned half-loaded. Bad options throw `INVALID_OPTION` naming the option.
 *
 * Animated and skinned assets are posed at `options.time` seconds (default 0) of
 * `options.animation` (an index or name; default the first animation, `null` for none): skinned
 * and morphed meshes are deformed on the CPU, animated nodes place meshes, cameras and lights.
 * `scene.pose({ time })` poses the loaded asset again without reading it again.
 */
export async function loadGltfScene(source: GltfSource, options: GltfLoadOptions = {}): Promise<GltfScene> {
  const { readGltfScene } = await import('./gltf-scene-reader.ts');
  return readGltfScene(source, options);
}
