// Texture memory in the frame stats, and a texture beyond the device's limits: downscaled with a
// warning in the renderer's snapshot and still rendered, never dropped.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { Document, TextureInfo } from '@gltf-transform/core';
import { encode as encodePng } from 'fast-png';
import { testDevice } from '../helpers/gpu.ts';
import { orthographicCameraNode, quad, renderScene, roundTrip } from './gltf-scenes.ts';

function texturedPlane(png: Uint8Array | undefined, configure?: (info: TextureInfo) => void): Document {
  const doc = new Document();
  const material = doc.createMaterial('plane').setMetallicFactor(0);
  if (png) {
    material.setBaseColorTexture(doc.createTexture('t').setMimeType('image/png').setImage(png));
    configure?.(material.getBaseColorTextureInfo()!);
  }
  doc.createScene().addChild(orthographicCameraNode(doc, 2)).addChild(doc.createNode('plane').setMesh(quad(doc, doc.createBuffer(), material, { x0: -1, y0: -1, x1: 1, y1: 1, normals: true })));
  return doc;
}

test('texture memory appears in the frame stats: at least the whole mip chain; only placeholder texels without textures', async () => {
  const size = 64;
  const data = Uint8Array.from({ length: size * size * 4 }, (_, i) => (i * 31) % 256);
  const textured = await renderScene(await roundTrip(texturedPlane(encodePng({ width: size, height: size, data, channels: 4 }))), { width: 8, height: 8 }, 1);
  const memory = textured.stats.memory;
  // Levels 64^2 + 32^2 + ... + 1 texels of 4 bytes each must be stored; packing into square
  // power-of-two layers may waste at most the rest of a layer four times the chain's size.
  let chain = 0;
  for (let s = size; s >= 1; s >>= 1) chain += 4 * s * s;
  assert.ok(memory.textureBytes >= chain && memory.textureBytes <= 4 * chain, `textureBytes ${memory.textureBytes}, mip chain ${chain}`);
  assert.ok(memory.sceneBytes >= memory.textureBytes && memory.totalBytes >= memory.sceneBytes + memory.queueBytes);
  assert.equal(textured.textureCount, 1);
  const plain = await renderScene(await roundTrip(texturedPlane(undefined)), { width: 8, height: 8 }, 1);
  // Without textures (and without an environment map) only the 1 x 1 placeholder texels the two
  // texture bindings need remain: the material atlas's (rgba8, 4 bytes) and the environment's
  // (rgba32float, 16 bytes).
  assert.ok(plain.stats.memory.textureBytes <= 4 + 16, `untextured textureBytes ${plain.stats.memory.textureBytes}`);
  assert.equal(plain.textureCount, 0);
});

test('a texture wider than maxTextureDimension2D is downscaled with a warning and still rendered', async () => {
  const device = await testDevice();
  const limit = device.limits.maxTextureDimension2D;
  // (limit + 1) x 2 texels: the left half red, the right half green; read without mipmaps, so only
  // level 0 has to fit: it is halved to floor((limit + 1) / 2) x 1.
  const width = limit + 1;
  const data = new Uint8Array(width * 2 * 4);
  for (let y = 0; y < 2; y++) for (let x = 0; x < width; x++) data.set(x < width / 2 ? [255, 0, 0, 255] : [0, 255, 0, 255], 4 * (y * width + x));
  const png = encodePng({ width, height: 2, data, channels: 4 });
  const scene = await roundTrip(texturedPlane(png, (info) => info.setMagFilter(TextureInfo.MagFilter.NEAREST).setMinFilter(TextureInfo.MinFilter.NEAREST)));
  assert.equal(scene.images[0]!.width, width, 'the loader keeps the image as it is');
  const result = await renderScene(scene, { width: 8, height: 8, aovs: true, environment: { color: [1, 1, 1] } }, 1);
  const warning = result.warnings.find((w) => w.startsWith('textures[0]:'));
  assert.ok(warning !== undefined && warning.includes(`${width}x2 downscaled`) && warning.includes(`maxTextureDimension2D ${limit}`), `warnings: ${JSON.stringify(result.warnings)}`);
  for (let y = 0; y < 8; y++) {
    for (let x = 0; x < 8; x++) {
      const [r, g] = [result.albedo![4 * (y * 8 + x)]!, result.albedo![4 * (y * 8 + x) + 1]!];
      // Pixel columns 0..3 cover u < 1/2 (red), 4..7 u > 1/2 (green); downscaling averages only
      // neighbouring texels, so away from the middle column the colours stay pure.
      assert.deepEqual([r, g].map((v) => Math.round(v * 1000) / 1000), x < 4 ? [1, 0] : [0, 1], `pixel (${x}, ${y})`);
    }
  }
});
