import { writeFileBytes } from '../platform.ts';
import { encodePng, type Rgba8Image } from './png.ts';

/** Encodes `image` as PNG and writes it to `path` (Node.js only; browser bundles never resolve `node:fs`). */
export async function writePng(path: string, image: Rgba8Image): Promise<void> {
  const bytes = encodePng(image);
  await writeFileBytes(path, bytes, 'writePng', 'use encodePng in browsers');
}
