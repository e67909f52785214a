// A KTX2 texture's own mip chain is the chain the renderers sample: a 64 x 64 KTX2 whose levels have
// distinct colours (level 0 red, 1 green, 2 blue, 3 white, ...), seen orthographically at 4 x 4
// texels per pixel (ray-cone lambda = 2, as in gltf-texture-lod.test.ts), shows level 2's blue.
// Levels filtered from level 0 would show red at every level.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { Document } from '@gltf-transform/core';
import { KHRMaterialsIOR, KHRTextureBasisu } from '@gltf-transform/extensions';
import { createDefaultContainer, write as writeKtx2 } from 'ktx-parse';
import { orthographicCameraNode, quad, renderScene, roundTrip } from './gltf-scenes.ts';
import { validateTextures } from '../../src/materials/textures/texture-input.ts';
import { isGpuRendererError } from '../../src/errors/gpu-renderer-error.ts';
import { createRasterRenderer } from '../../src/raster/index.ts';
import { testDevice } from '../helpers/gpu.ts';

const SIZE = 64;
const LEVEL_COLOURS = [[255, 0, 0], [0, 255, 0], [0, 0, 255], [255, 255, 255], [128, 128, 128], [0, 255, 255], [255, 0, 255]] as const;

/** R8G8B8A8_SRGB, uncompressed, every level of the 64 x 64 chain filled with its colour. */
function levelsKtx2(levelCount: number = LEVEL_COLOURS.length): Uint8Array {
  const levels = LEVEL_COLOURS.slice(0, levelCount).map((rgb, k) => {
    const n = Math.max(1, SIZE >> k) ** 2;
    const levelData = new Uint8Array(4 * n);
    for (let p = 0; p < n; p++) levelData.set([...rgb, 255], 4 * p);
    return { levelData, uncompressedByteLength: levelData.length };
  });
  const container = createDefaultContainer();
  Object.assign(container, { vkFormat: 43, typeSize: 1, pixelWidth: SIZE, pixelHeight: SIZE, supercompressionScheme: 0, levelCount: levels.length, levels });
  container.dataFormatDescriptor[0]!.bytesPlane[0] = 4;
  return writeKtx2(container);
}

function texturedPlane(ktx2: Uint8Array): Document {
  const doc = new Document();
  doc.createExtension(KHRTextureBasisu).setRequired(true);
  const texture = doc.createTexture('levels').setMimeType('image/ktx2').setImage(ktx2);
  const material = doc.createMaterial('levels').setMetallicFactor(0).setBaseColorTexture(texture)
    .setExtension('KHR_materials_ior', doc.createExtension(KHRMaterialsIOR).createIOR().setIOR(1));
  const plane = quad(doc, doc.createBuffer(), material, { x0: -1, y0: -1, x1: 1, y1: 1, normals: true });
  doc.createScene().addChild(orthographicCameraNode(doc, 2)).addChild(doc.createNode('plane').setMesh(plane));
  return doc;
}

test('the glTF loader keeps every level of a KTX2 file; stored levels of the wrong size are refused naming the level', async () => {
  const scene = await roundTrip(texturedPlane(levelsKtx2()));
  const image = scene.images[0]!;
  assert.deepEqual([image.width, image.height, image.data[0], image.data[1]], [SIZE, SIZE, 255, 0]);
  assert.deepEqual(image.mipLevels!.map((l) => [l.width, l.height, ...l.data.subarray(0, 3)]), LEVEL_COLOURS.slice(1).map((rgb, k) => [SIZE >> (k + 1), SIZE >> (k + 1), ...rgb]));
  const shortChain = (await roundTrip(texturedPlane(levelsKtx2(3)))).images[0]!;
  assert.equal(shortChain.mipLevels!.length, 2);
  const wrong = { ...image, mipLevels: [image.mipLevels![1]!] };
  assert.throws(() => validateTextures([{ image: 0 }], [wrong]), (e) => isGpuRendererError(e) && e.code === 'INVALID_TEXTURE' && e.field === 'images[0].mipLevels[0]' && /level 1 of a 64 x 64 image is 32 x 32, got 16 x 16/.test(e.message));
});

test("the path tracer samples a KTX2 file's own mip levels: 4 x 4 texels per pixel show level 2", async () => {
  const result = await renderScene(await roundTrip(texturedPlane(levelsKtx2())), { width: 16, height: 16, aovs: true, environment: { color: [1, 1, 1] }, maxDepth: 1 }, 1);
  for (let p = 0; p < 256; p++) {
    const albedo = [...result.albedo!.subarray(4 * p, 4 * p + 3)];
    assert.ok(Math.abs(albedo[0]!) < 1e-3 && Math.abs(albedo[1]!) < 1e-3 && Math.abs(albedo[2]! - 1) < 1e-3, `pixel ${p}: albedo ${albedo} (level 2 is blue)`);
  }
  // A file with levels 0..2 only: the levels below come from level 0 (red), level 2 is still the file's.
  const short = await renderScene(await roundTrip(texturedPlane(levelsKtx2(3))), { width: 16, height: 16, aovs: true, environment: { color: [1, 1, 1] }, maxDepth: 1 }, 1);
  assert.ok(Math.abs(short.albedo![2]! - 1) < 1e-3 && Math.abs(short.albedo![0]!) < 1e-3, `short chain: ${[...short.albedo!.subarray(0, 3)]}`);
});

test("the raster renderer samples a KTX2 file's own mip levels too", async () => {
  const scene = await roundTrip(texturedPlane(levelsKtx2()));
  const renderer = await createRasterRenderer({ ...scene, device: await testDevice(), width: 16, height: 16, toneMapping: 'linear', shadow: false, environment: { color: [1, 1, 1] } });
  try {
    await renderer.render();
    const { data } = await renderer.readPixels();
    // The centre 8 x 8 pixels: well inside the plane, away from the hardware's 2 x 2 derivative quads at the edges.
    for (let y = 4; y < 12; y++) {
      for (let x = 4; x < 12; x++) {
        const p = 4 * (y * 16 + x);
        assert.ok(data[p]! <= 2 && data[p + 1]! <= 2 && data[p + 2]! >= 250, `pixel (${x}, ${y}): ${[...data.subarray(p, p + 3)]} (level 2 is blue)`);
      }
    }
  } finally {
    renderer.destroy();
  }
});
