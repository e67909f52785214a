// Texture codecs end to end through loadGltfScene: KTX2 (KHR_texture_basisu: Basis Universal ETC1S
// and UASTC; uncompressed KTX2 with zlib and Zstandard supercompression) and AVIF
// (EXT_texture_avif). The fixtures were encoded from codecPattern() (fixtures/make-codec-fixtures.ts);
// each decoded image is compared with the lossless PNG of the same pattern. ETC1S is the coarse
// codec (measured mean error 7.7 / 3.8 / 11.2 / 1.2 levels of 255 in R, G, B, A), UASTC the fine
// one (0.9 / 2.5 / 4.0 / 2.0), lossless AVIF exact; a flipped, shifted or channel-swapped decode
// misses these bounds by tens of levels.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { Document } from '@gltf-transform/core';
import { EXTTextureAVIF, KHRTextureBasisu } from '@gltf-transform/extensions';
import { createDefaultContainer, read as readKtx2, write as writeKtx2 } from 'ktx-parse';
import { decompress } from 'fzstd';
import { zlibSync } from 'fflate';
import { loadGltfScene } from '../../../src/io/index.ts';
import { codecPattern, patternSize } from './codec-pattern.ts';
import { createIO, quadMesh, rejectsWith, toGlb } from './helpers.ts';

const fixture = (name: string): Uint8Array => new Uint8Array(readFileSync(new URL(`./fixtures/${name}`, import.meta.url)));

/** A one-quad asset whose base colour texture is `bytes`, under the texture extension `ext`. */
async function texturedAsset(bytes: Uint8Array, mimeType: string, ext?: typeof KHRTextureBasisu | typeof EXTTextureAVIF): Promise<Uint8Array> {
  const doc = new Document();
  if (ext === KHRTextureBasisu) doc.createExtension(KHRTextureBasisu).setRequired(true);
  else if (ext === EXTTextureAVIF) doc.createExtension(EXTTextureAVIF).setRequired(true);
  const texture = doc.createTexture('pattern').setMimeType(mimeType).setImage(bytes);
  doc.createScene().addChild(doc.createNode('n').setMesh(quadMesh(doc, doc.createBuffer(), doc.createMaterial('m').setBaseColorTexture(texture))));
  return toGlb(doc);
}

/** Mean absolute error per channel (levels of 255) between two RGBA8 images. */
function meanError(actual: ArrayLike<number>, expected: ArrayLike<number>): number[] {
  assert.equal(actual.length, expected.length);
  const error = [0, 0, 0, 0];
  for (let i = 0; i < expected.length; i++) error[i % 4]! += Math.abs(actual[i]! - expected[i]!) / (expected.length / 4);
  return error;
}

async function decodedBaseColor(glb: Uint8Array): Promise<Uint8Array | Uint8ClampedArray> {
  const scene = await loadGltfScene(glb);
  assert.deepEqual(scene.warnings, []);
  assert.equal(scene.materials[0]!.baseColorTexture!.index, 0);
  const image = scene.images[0]!;
  assert.deepEqual([image.width, image.height], [patternSize, patternSize]);
  return image.data;
}

test('the PNG fixture is the pattern, losslessly', async () => {
  assert.deepEqual([...(await decodedBaseColor(await texturedAsset(fixture('pattern.png'), 'image/png')))], [...codecPattern()]);
});

test('KHR_texture_basisu (required): ETC1S and UASTC KTX2 transcode to the PNG source within the codecs\' error', async () => {
  const reference = codecPattern();
  const etc1s = meanError(await decodedBaseColor(await texturedAsset(fixture('pattern-etc1s.ktx2'), 'image/ktx2', KHRTextureBasisu)), reference);
  etc1s.forEach((e, c) => assert.ok(e <= 14, `ETC1S channel ${c}: mean error ${e.toFixed(2)}`));
  const uastc = meanError(await decodedBaseColor(await texturedAsset(fixture('pattern-uastc.ktx2'), 'image/ktx2', KHRTextureBasisu)), reference);
  uastc.forEach((e, c) => assert.ok(e <= 5, `UASTC channel ${c}: mean error ${e.toFixed(2)}`));
});

test('optional KHR_texture_basisu with a PNG fallback: the KTX2 source is the one decoded', async () => {
  const doc = new Document();
  doc.createExtension(KHRTextureBasisu).setRequired(false);
  const texture = doc.createTexture('pattern').setMimeType('image/ktx2').setImage(fixture('pattern-uastc.ktx2'));
  doc.createScene().addChild(doc.createNode('n').setMesh(quadMesh(doc, doc.createBuffer(), doc.createMaterial('m').setBaseColorTexture(texture))));
  const { json, resources } = await createIO().writeJSON(doc);
  const inline = (bytes: Uint8Array, type: string): string => `data:${type};base64,${Buffer.from(bytes).toString('base64')}`;
  json.buffers![0]!.uri = inline(resources[json.buffers![0]!.uri!]!, 'application/octet-stream');
  json.images![0]!.uri = inline(fixture('pattern-uastc.ktx2'), 'image/ktx2');
  // The fallback: the lossless PNG of the pattern, which would decode exactly.
  json.images!.push({ uri: inline(readFileSync(new URL('./fixtures/pattern.png', import.meta.url)), 'image/png') });
  json.textures![0]!.source = 1;
  const scene = await loadGltfScene(new TextEncoder().encode(JSON.stringify(json)));
  assert.equal(scene.images.length, 1);
  // UASTC error, not the exact PNG: the KTX2 was decoded.
  const error = meanError(scene.images[0]!.data, codecPattern());
  assert.ok(error.some((e) => e > 0.5) && error.every((e) => e <= 5), `mean error ${error.map((e) => e.toFixed(2))}`);
});

/** A zstd frame holding `data` as raw blocks (RFC 8878 section 3.1): what fzstd must read back. */
function zstdRawFrame(data: Uint8Array): Uint8Array {
  const blocks: number[] = [];
  const max = 1 << 17;
  for (let at = 0; at < data.length || at === 0; at += max) {
    const size = Math.min(max, data.length - at);
    const header = (size << 3) | (at + size >= data.length ? 1 : 0);
    blocks.push(header & 0xff, (header >> 8) & 0xff, (header >> 16) & 0xff, ...data.subarray(at, at + size));
    if (data.length === 0) break;
  }
  // Frame header: single segment, 4-byte content size (FCS flag 2).
  const size = data.length;
  return new Uint8Array([0x28, 0xb5, 0x2f, 0xfd, 0xa0, size & 0xff, (size >> 8) & 0xff, (size >> 16) & 0xff, size >>> 24, ...blocks]);
}

function plainKtx2(vkFormat: number, channels: number, levelData: Uint8Array, supercompressionScheme: number, uncompressed: number, orientation?: string): Uint8Array {
  const container = createDefaultContainer();
  Object.assign(container, { vkFormat, typeSize: 1, pixelWidth: patternSize, pixelHeight: patternSize, supercompressionScheme, levels: [{ levelData, uncompressedByteLength: uncompressed }] });
  container.dataFormatDescriptor[0]!.bytesPlane[0] = channels;
  if (orientation) container.keyValue.KTXorientation = orientation;
  return writeKtx2(container);
}

test('uncompressed KTX2 as an image source: RGBA8 with zlib, RGB8 with Zstandard, BGRA8 stored bottom row first', async () => {
  const pattern = codecPattern();
  const rgbaZlib = plainKtx2(37, 4, zlibSync(pattern), 3, pattern.length);
  assert.deepEqual([...(await decodedBaseColor(await texturedAsset(rgbaZlib, 'image/ktx2', KHRTextureBasisu)))], [...pattern]);

  const rgb = new Uint8Array(patternSize * patternSize * 3);
  const opaque = pattern.slice();
  for (let p = 0; p < patternSize * patternSize; p++) {
    for (let c = 0; c < 3; c++) rgb[p * 3 + c] = pattern[p * 4 + c]!;
    opaque[p * 4 + 3] = 255;
  }
  const rgbZstd = plainKtx2(23, 3, zstdRawFrame(rgb), 2, rgb.length);
  assert.deepEqual([...(await decodedBaseColor(await texturedAsset(rgbZstd, 'image/ktx2', KHRTextureBasisu)))], [...opaque]);

  // B8G8R8A8_SRGB, rows bottom first ("ru"): the loader swaps channels and flips rows.
  const row = patternSize * 4;
  const bgraUp = new Uint8Array(pattern.length);
  for (let y = 0; y < patternSize; y++) {
    for (let x = 0; x < patternSize; x++) {
      const s = y * row + x * 4;
      const d = (patternSize - 1 - y) * row + x * 4;
      bgraUp.set([pattern[s + 2]!, pattern[s + 1]!, pattern[s]!, pattern[s + 3]!], d);
    }
  }
  const bgra = plainKtx2(50, 4, bgraUp, 0, bgraUp.length, 'ru');
  assert.deepEqual([...(await decodedBaseColor(await texturedAsset(bgra, 'image/ktx2', KHRTextureBasisu)))], [...pattern]);
});

test('a Basis Universal (UASTC) KTX2 with a mip chain: every level is transcoded into mipLevels, block for block', async () => {
  // UASTC codes each 4 x 4 block on its own, so levels made of blocks of level 0 (the fixture's
  // first 16, 4 and 1 blocks) must transcode to exactly those blocks' texels of level 0.
  const container = readKtx2(fixture('pattern-uastc.ktx2'));
  const level0 = decompress(container.levels[0]!.levelData, new Uint8Array(container.levels[0]!.uncompressedByteLength));
  const blockCounts = [16, 4, 1, 1, 1];
  const levels = [level0, ...blockCounts.map((n) => level0.slice(0, 16 * n))].map((levelData) => ({ levelData, uncompressedByteLength: levelData.length }));
  Object.assign(container, { supercompressionScheme: 0, levelCount: levels.length, levels });
  const scene = await loadGltfScene(await texturedAsset(writeKtx2(container), 'image/ktx2', KHRTextureBasisu));
  const image = scene.images[0]!;
  assert.deepEqual(image.mipLevels!.map((l) => [l.width, l.height]), [[16, 16], [8, 8], [4, 4], [2, 2], [1, 1]]);
  const blocksPerRow0 = patternSize / 4;
  image.mipLevels!.forEach((level, k) => {
    const blocksPerRow = Math.ceil(level.width / 4);
    for (let y = 0; y < level.height; y++) {
      for (let x = 0; x < level.width; x++) {
        const block = (y >> 2) * blocksPerRow + (x >> 2);
        const from = 4 * (((block / blocksPerRow0) | 0) * 4 + (y & 3)) * patternSize + 4 * ((block % blocksPerRow0) * 4 + (x & 3));
        assert.deepEqual([...level.data.subarray(4 * (y * level.width + x), 4 * (y * level.width + x) + 4)], [...image.data.subarray(from, from + 4)], `level ${k + 1} texel (${x}, ${y})`);
      }
    }
  });
});

test('EXT_texture_avif (required): the lossless AVIF decodes to the PNG source exactly; a broken one names its image', async () => {
  assert.deepEqual([...(await decodedBaseColor(await texturedAsset(fixture('pattern.avif'), 'image/avif', EXTTextureAVIF)))], [...codecPattern()]);
  const broken = fixture('pattern.avif').slice(0, 200);
  await rejectsWith(loadGltfScene(await texturedAsset(broken, 'image/avif', EXTTextureAVIF)), 'INVALID_GLTF', '/images/0', /AVIF image does not decode/);
});
