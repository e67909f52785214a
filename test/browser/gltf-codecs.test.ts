// A real browser (Debian's Chromium) loads a .glb whose textures are KTX2 (KHR_texture_basisu,
// ETC1S and UASTC) and AVIF (EXT_texture_avif): the package's browser build transcodes the KTX2
// with the same embedded Basis transcoder as Node (identical texels), and the browser decodes the
// AVIF itself (createImageBitmap) to Node's libavif colours, but for the premultiplied-alpha
// rounding of the canvas it is read back through (a few levels where alpha < 255).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { Document, NodeIO } from '@gltf-transform/core';
import { ALL_EXTENSIONS, EXTTextureAVIF, KHRTextureBasisu } from '@gltf-transform/extensions';
import { loadGltfScene } from '../../src/io/index.ts';
import type * as Pkg from '../../src/index.ts';
import { chromiumSkip, openPackagePage } from './browser-session.ts';

const fixture = (name: string): Uint8Array => new Uint8Array(readFileSync(new URL(`../io/gltf/fixtures/${name}`, import.meta.url)));

async function asset(): Promise<Uint8Array> {
  const doc = new Document();
  doc.createExtension(KHRTextureBasisu).setRequired(true);
  doc.createExtension(EXTTextureAVIF).setRequired(true);
  const buffer = doc.createBuffer();
  const textures = [
    doc.createTexture('etc1s').setMimeType('image/ktx2').setImage(fixture('pattern-etc1s.ktx2')),
    doc.createTexture('uastc').setMimeType('image/ktx2').setImage(fixture('pattern-uastc.ktx2')),
    doc.createTexture('avif').setMimeType('image/avif').setImage(fixture('pattern.avif')),
  ];
  const scene = doc.createScene();
  textures.forEach((texture, i) => {
    const p = new Float32Array([0, 0, -i, 1, 0, -i, 1, 1, -i]);
    const primitive = doc.createPrimitive()
      .setAttribute('POSITION', doc.createAccessor().setType('VEC3').setArray(p).setBuffer(buffer))
      .setAttribute('TEXCOORD_0', doc.createAccessor().setType('VEC2').setArray(new Float32Array([0, 1, 1, 1, 1, 0])).setBuffer(buffer))
      .setMaterial(doc.createMaterial(texture.getName()).setBaseColorTexture(texture));
    scene.addChild(doc.createNode(texture.getName()).setMesh(doc.createMesh().addPrimitive(primitive)));
  });
  return new NodeIO().registerExtensions(ALL_EXTENSIONS).writeBinary(doc);
}

test('Chromium: KTX2 (Basis ETC1S, UASTC) transcodes as in Node; AVIF decodes natively to libavif\'s colours', { skip: chromiumSkip, timeout: 240_000 }, async (t) => {
  const glb = await asset();
  const node = await loadGltfScene(glb);
  const { tab, pageErrors, close } = await openPackagePage({ style: '', body: '', viewport: { width: 64, height: 64 } });
  t.after(close);
  const images = await tab.evaluate(async (bytes: number[]) => {
    const { loadGltfScene } = (window as unknown as { pkg: typeof Pkg }).pkg;
    const scene = await loadGltfScene(Uint8Array.from(bytes));
    return { warnings: [...scene.warnings], images: scene.images.map((image) => ({ width: image.width, height: image.height, data: Array.from(image.data) })) };
  }, Array.from(glb));
  assert.deepEqual(pageErrors, []);
  assert.deepEqual(images.warnings, []);
  assert.equal(images.images.length, 3);
  images.images.forEach((image, i) => {
    const reference = node.images[i]!;
    assert.deepEqual([image.width, image.height], [reference.width, reference.height]);
    for (let k = 0; k < image.data.length; k++) {
      // The AVIF's alpha plane: Chromium expands it as limited range (250 -> 255, 172 -> 182),
      // libavif reads it as full range (the pattern's own values); only its colour is compared.
      if (i === 2 && k % 4 === 3) continue;
      const alpha = reference.data[4 * Math.floor(k / 4) + 3]!;
      const allowed = i < 2 ? 0 : Math.ceil(255 / alpha);
      assert.ok(Math.abs(image.data[k]! - reference.data[k]!) <= allowed, `image ${i} byte ${k}: browser ${image.data[k]}, Node ${reference.data[k]}`);
    }
  });
});
