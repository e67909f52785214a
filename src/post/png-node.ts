import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import { encodePng, type Rgba8Image } from './png.ts';

/**
 * Encodes `image` as PNG and writes it to `path` (Node.js only). `node:fs` is imported lazily
 * through a variable specifier, as src/gpu/acquire-device.ts does for Dawn, so browser bundles that
 * include the package entry never try to resolve it.
 */
export async function writePng(path: string, image: Rgba8Image): Promise<void> {
  const bytes = encodePng(image);
  const isNode = typeof process !== 'undefined' && typeof process.versions?.node === 'string';
  if (!isNode) throw new GpuRendererError('INVALID_STATE', 'writePng needs Node.js (node:fs); use encodePng in browsers');
  const specifier = 'node:fs/promises';
  const fs = (await import(specifier)) as { writeFile: (path: string, data: Uint8Array) => Promise<void> };
  await fs.writeFile(path, bytes);
}
