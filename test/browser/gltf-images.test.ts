// A real browser: Debian's Chromium loads a .glb with loadGltfScene, as bytes and by URL. Its PNG,
// JPEG and WebP images must decode through the platform (createImageBitmap, counted by a spy)
// to the texels Node's pure-JS/wasm decoders give, and the loaded scene must render its texture on
// the page's WebGPU device.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { Document, NodeIO, TextureInfo } from '@gltf-transform/core';
import { ALL_EXTENSIONS, EXTTextureWebP, KHRMaterialsIOR } from '@gltf-transform/extensions';
import { encode as encodePng } from 'fast-png';
import jpeg from 'jpeg-js';
import webp from 'webp-wasm';
import { loadGltfScene } from '../../src/io/index.ts';
import { srgbToLinear } from '../../src/film/tone-mapping.ts';
import type * as Pkg from '../../src/index.ts';
import { chromiumSkip, openPackagePage } from './browser-session.ts';

/** 2 x 2 texels, one of them half transparent (the canvas path stores premultiplied alpha). */
const PIXELS = [250, 30, 10, 255, 20, 220, 90, 255, 60, 90, 240, 255, 255, 255, 255, 128];

async function asset(): Promise<Uint8Array> {
  const doc = new Document();
  doc.createExtension(EXTTextureWebP);
  const ior = doc.createExtension(KHRMaterialsIOR);
  const buffer = doc.createBuffer();
  const jw = 16;
  const jdata = new Uint8Array(jw * jw * 4);
  for (let p = 0; p < jw * jw; p++) jdata.set(p % jw < 8 ? [200, 40, 30, 255] : [20, 90, 220, 255], p * 4);
  const images = [
    doc.createTexture('png').setMimeType('image/png').setImage(encodePng({ width: 2, height: 2, data: Uint8Array.from(PIXELS), channels: 4 })),
    doc.createTexture('jpeg').setMimeType('image/jpeg').setImage(new Uint8Array(jpeg.encode({ width: jw, height: jw, data: jdata }, 95).data)),
    doc.createTexture('webp').setMimeType('image/webp').setImage(new Uint8Array(await webp.encode({ data: new Uint8ClampedArray(PIXELS), width: 2, height: 2 }, { lossless: 1, exact: 1 }))),
  ];
  const scene = doc.createScene();
  const camera = doc.createCamera('ortho').setType('orthographic').setYMag(1).setXMag(1).setZNear(0.01).setZFar(10);
  scene.addChild(doc.createNode('camera').setCamera(camera).setTranslation([0, 0, 2]));
  images.forEach((image, i) => {
    // Emitters of radiance exactly their texels (black base colour, ior 1: nothing reflected).
    const material = doc.createMaterial(image.getName()).setBaseColorFactor([0, 0, 0, 1]).setEmissiveFactor([1, 1, 1]).setEmissiveTexture(image)
      .setExtension('KHR_materials_ior', ior.createIOR().setIOR(1));
    material.getEmissiveTextureInfo()!.setMagFilter(TextureInfo.MagFilter.NEAREST).setMinFilter(TextureInfo.MinFilter.NEAREST);
    const z = -i; // the PNG quad in front, the others behind it
    const p = new Float32Array([-1, -1, z, 1, -1, z, 1, 1, z, -1, 1, z]);
    const primitive = doc.createPrimitive()
      .setAttribute('POSITION', doc.createAccessor().setType('VEC3').setArray(p).setBuffer(buffer))
      .setAttribute('TEXCOORD_0', doc.createAccessor().setType('VEC2').setArray(new Float32Array([0, 1, 1, 1, 1, 0, 0, 0])).setBuffer(buffer))
      .setIndices(doc.createAccessor().setType('SCALAR').setArray(new Uint16Array([0, 1, 2, 0, 2, 3])).setBuffer(buffer))
      .setMaterial(material);
    scene.addChild(doc.createNode(image.getName()).setMesh(doc.createMesh().addPrimitive(primitive)));
  });
  return new NodeIO().registerExtensions(ALL_EXTENSIONS).writeBinary(doc);
}

interface PageResult {
  bitmapCalls: number;
  fromBytes: { width: number; height: number; data: number[] }[];
  fromUrl: { width: number; height: number; data: number[] }[];
  radiance: number[];
}

test('Chromium: loadGltfScene decodes PNG, JPEG and WebP with createImageBitmap like Node does, and the texture renders', { skip: chromiumSkip, timeout: 240_000 }, async (t) => {
  const glb = await asset();
  const node = await loadGltfScene(glb);
  const { tab, pageErrors, close } = await openPackagePage({ style: '', body: '', viewport: { width: 64, height: 64 } });
  t.after(close);
  const result = await tab.evaluate(async (bytes: number[]): Promise<PageResult> => {
    const { loadGltfScene, createWavefrontPathTracingComputeRenderer } = (window as unknown as { pkg: typeof Pkg }).pkg;
    const original = window.createImageBitmap.bind(window);
    let bitmapCalls = 0;
    (window as unknown as { createImageBitmap: typeof createImageBitmap }).createImageBitmap = ((...args: Parameters<typeof createImageBitmap>) => {
      bitmapCalls++;
      return original(...args);
    }) as typeof createImageBitmap;
    const glb = Uint8Array.from(bytes);
    const plain = (scene: Awaited<ReturnType<typeof loadGltfScene>>) => scene.images.map((image) => ({ width: image.width, height: image.height, data: Array.from(image.data) }));
    const scene = await loadGltfScene(glb);
    const url = URL.createObjectURL(new Blob([glb], { type: 'model/gltf-binary' }));
    const byUrl = await loadGltfScene(url);
    URL.revokeObjectURL(url);
    const renderer = await createWavefrontPathTracingComputeRenderer({ ...scene, width: 4, height: 4, samplesPerPixel: 2, maxDepth: 2, environment: { color: [0, 0, 0] } });
    await renderer.renderFrame();
    const radiance = Array.from((await renderer.readRadiance()).data);
    renderer.destroy();
    return { bitmapCalls, fromBytes: plain(scene), fromUrl: plain(byUrl), radiance };
  }, Array.from(glb));
  assert.deepEqual(pageErrors, []);
  assert.equal(result.bitmapCalls, 6, 'three images decoded through createImageBitmap, twice');
  for (const images of [result.fromBytes, result.fromUrl]) {
    assert.equal(images.length, 3);
    images.forEach((image, i) => {
      const reference = node.images[i]!;
      assert.deepEqual([image.width, image.height], [reference.width, reference.height]);
      // PNG and lossless WebP: exact, but for the colour of the half-transparent texel, which the
      // canvas stores premultiplied (±1). JPEG: two decoders' IDCTs (libjpeg-turbo, jpeg-js) may
      // differ by a few levels.
      const tolerance = i === 1 ? 3 : 0;
      for (let k = 0; k < image.data.length; k++) {
        const allowed = reference.data[4 * Math.floor(k / 4) + 3]! < 255 && k % 4 !== 3 ? 1 : tolerance;
        assert.ok(Math.abs(image.data[k]! - reference.data[k]!) <= allowed, `image ${i} byte ${k}: browser ${image.data[k]}, Node ${reference.data[k]}`);
      }
    });
  }
  // The 4 x 4 image of the PNG quad: each 2 x 2 block of pixels shows one texel's decoded radiance.
  for (let y = 0; y < 4; y++) {
    for (let x = 0; x < 4; x++) {
      const texel = 2 * (y >> 1) + (x >> 1);
      for (let c = 0; c < 3; c++) {
        const want = srgbToLinear(result.fromBytes[0]!.data[4 * texel + c]! / 255);
        const got = result.radiance[4 * (y * 4 + x) + c]!;
        assert.ok(Math.abs(got - want) < 1e-5, `pixel (${x}, ${y}) channel ${c}: ${got} vs ${want}`);
      }
    }
  }
});
