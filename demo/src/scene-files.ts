// Scenes from the user's files: a .glb, or a .gltf with the .bin and image files it names (picked
// or dropped together). A .gltf's external resources are matched to the given files by name and
// handed to the loader as blob: URLs, so nothing is fetched from anywhere else.
import { loadGltfScene } from '@plasius/gpu-renderer';
import type { DemoScene } from './scenes/types.ts';

/** Uniform environment for a loaded asset, which brings no lighting of its own in most cases. */
const assetEnvironment: [number, number, number] = [0.9, 0.9, 0.9];

export const acceptedExtensions = ['.glb', '.gltf'];

export function isSceneFile(name: string): boolean {
  const lower = name.toLowerCase();
  return acceptedExtensions.some((ext) => lower.endsWith(ext));
}

export async function sceneFromFiles(files: readonly File[]): Promise<DemoScene> {
  const main = files.find((f) => isSceneFile(f.name));
  if (!main) throw new Error(`expected a .glb or .gltf file, got ${files.map((f) => f.name).join(', ') || 'nothing'}`);
  const urls: string[] = [];
  try {
    const source = main.name.toLowerCase().endsWith('.glb') ? new Uint8Array(await main.arrayBuffer()) : await gltfWithResources(main, files, urls);
    const scene = await loadGltfScene(source);
    const { camera, ...rest } = scene;
    return {
      name: main.name.replace(/\.(glb|gltf)$/i, ''),
      description: { ...rest, camera },
      suggestedEnvironment: assetEnvironment,
      notes: [...scene.warnings],
    };
  } finally {
    for (const url of urls) URL.revokeObjectURL(url);
  }
}

/** The .gltf as a blob: URL whose external URIs point at blob: URLs of the matching files. */
async function gltfWithResources(main: File, files: readonly File[], urls: string[]): Promise<URL> {
  const json = JSON.parse(await main.text()) as { buffers?: { uri?: string }[]; images?: { uri?: string }[] };
  const byName = new Map(files.map((f) => [f.name, f]));
  const resolve = (entry: { uri?: string }): void => {
    if (!entry.uri || entry.uri.startsWith('data:')) return;
    const name = decodeURIComponent(entry.uri).split('/').pop()!;
    const file = byName.get(name);
    if (!file) return; // left as it is: the loader names the missing resource
    const url = URL.createObjectURL(file);
    urls.push(url);
    entry.uri = url;
  };
  json.buffers?.forEach(resolve);
  json.images?.forEach(resolve);
  const url = URL.createObjectURL(new Blob([JSON.stringify(json)], { type: 'model/gltf+json' }));
  urls.push(url);
  return new URL(url);
}
