// End to end: a .glb dropped on the demo page is loaded (images decoded by the browser), path
// traced and converges, with no console errors. The asset is generated here with
// @gltf-transform/core: an orange-and-red checker-textured cube on a grey floor.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { join } from 'node:path';
import { Document, WebIO } from '@gltf-transform/core';
import { encode } from 'fast-png';
import { captureAtLeast, chromiumSkip, ensureTestOutputDir, meanAbsoluteDifference, openDemo } from './demo-page.ts';

const width = 64;
const height = 48;

/** A unit cube (24 vertices, flat normals, uvs per face) and a floor quad, as a GLB. */
async function cubeOnFloorGlb(): Promise<Uint8Array> {
  const doc = new Document();
  const buffer = doc.createBuffer();
  const positions: number[] = [];
  const normals: number[] = [];
  const uvs: number[] = [];
  const indices: number[] = [];
  const faces: [number[], number[], number[]][] = [
    // normal, u axis, v axis (u x v = normal, so each face winds counter-clockwise from outside)
    [[1, 0, 0], [0, 0, -1], [0, 1, 0]],
    [[-1, 0, 0], [0, 0, 1], [0, 1, 0]],
    [[0, 1, 0], [1, 0, 0], [0, 0, -1]],
    [[0, -1, 0], [1, 0, 0], [0, 0, 1]],
    [[0, 0, 1], [1, 0, 0], [0, 1, 0]],
    [[0, 0, -1], [-1, 0, 0], [0, 1, 0]],
  ];
  for (const [n, u, v] of faces) {
    const base = positions.length / 3;
    for (const [su, sv] of [[-1, -1], [1, -1], [1, 1], [-1, 1]] as const) {
      for (let i = 0; i < 3; i++) positions.push(0.5 * (n[i]! + su * u[i]! + sv * v[i]!));
      normals.push(...n);
      uvs.push((su + 1) / 2, (1 - sv) / 2);
    }
    indices.push(base, base + 1, base + 2, base, base + 2, base + 3);
  }
  const texels = new Uint8Array(4 * 4 * 4);
  for (let i = 0; i < 16; i++) texels.set((i + (i >> 2)) % 2 ? [230, 60, 30, 255] : [240, 150, 40, 255], 4 * i);
  const texture = doc.createTexture('checker').setImage(encode({ width: 4, height: 4, data: texels, channels: 4 })).setMimeType('image/png');
  const cubeMaterial = doc.createMaterial('cube').setBaseColorTexture(texture).setMetallicFactor(0).setRoughnessFactor(0.6);
  const floorMaterial = doc.createMaterial('floor').setBaseColorFactor([0.5, 0.5, 0.5, 1]).setMetallicFactor(0).setRoughnessFactor(1);
  const accessor = (type: 'VEC3' | 'VEC2' | 'SCALAR', array: Float32Array<ArrayBuffer> | Uint16Array<ArrayBuffer>) => doc.createAccessor().setType(type).setArray(array).setBuffer(buffer);
  const cube = doc.createPrimitive()
    .setAttribute('POSITION', accessor('VEC3', new Float32Array(positions)))
    .setAttribute('NORMAL', accessor('VEC3', new Float32Array(normals)))
    .setAttribute('TEXCOORD_0', accessor('VEC2', new Float32Array(uvs)))
    .setIndices(accessor('SCALAR', new Uint16Array(indices)))
    .setMaterial(cubeMaterial);
  const floor = doc.createPrimitive()
    .setAttribute('POSITION', accessor('VEC3', new Float32Array([-3, -0.5, 3, 3, -0.5, 3, 3, -0.5, -3, -3, -0.5, -3])))
    .setIndices(accessor('SCALAR', new Uint16Array([0, 1, 2, 0, 2, 3])))
    .setMaterial(floorMaterial);
  const cubeNode = doc.createNode('cube').setMesh(doc.createMesh('cube').addPrimitive(cube)).setRotation([0, Math.sin(Math.PI / 8), 0, Math.cos(Math.PI / 8)]);
  const floorNode = doc.createNode('floor').setMesh(doc.createMesh('floor').addPrimitive(floor));
  const cameraNode = doc.createNode('camera')
    .setCamera(doc.createCamera('camera').setType('perspective').setYFov(0.7).setAspectRatio(4 / 3).setZNear(0.05))
    .setTranslation([0, 0.9, 3.2])
    .setRotation([-Math.sin(0.13), 0, 0, Math.cos(0.13)]);
  doc.createScene('scene').addChild(cubeNode).addChild(floorNode).addChild(cameraNode);
  return new WebIO().writeBinary(doc);
}

test('demo: a dropped .glb renders, converges and shows its texture', { skip: chromiumSkip, timeout: 240_000 }, async (t) => {
  const glb = await cubeOnFloorGlb();
  const { tab, errors, close } = await openDemo(`?scene=cornell&size=${width}x${height}&spf=2&stop=32`);
  t.after(close);
  // Wait for the first scene, then drop the file on the picture as a browser would deliver it.
  await captureAtLeast(tab, 2, 90_000);
  await tab.evaluate((bytes) => {
    const transfer = new DataTransfer();
    transfer.items.add(new File([new Uint8Array(bytes)], 'cube-on-floor.glb', { type: 'model/gltf-binary' }));
    const viewport = document.getElementById('viewport')!;
    viewport.dispatchEvent(new DragEvent('dragenter', { dataTransfer: transfer, bubbles: true }));
    viewport.dispatchEvent(new DragEvent('drop', { dataTransfer: transfer, bubbles: true, cancelable: true }));
  }, Array.from(glb));
  await tab.waitForFunction(() => document.querySelector<HTMLSelectElement>('[data-control="scene"]')?.value === 'file', undefined, { timeout: 30_000 });
  await tab.waitForFunction(() => /^14 triangles/.test(document.querySelector('[data-readout="status"]')?.textContent ?? ''), undefined, { timeout: 60_000 });

  const a = await captureAtLeast(tab, 2, 90_000);
  const b = await captureAtLeast(tab, 8, 90_000);
  const c = await captureAtLeast(tab, 32, 90_000);
  const early = meanAbsoluteDifference(a, b);
  const late = meanAbsoluteDifference(b, c);
  t.diagnostic(`mean |difference| ${a.samples}->${b.samples} spp: ${early.toFixed(3)}, ${b.samples}->${c.samples} spp: ${late.toFixed(3)} (8-bit steps)`);
  assert.ok(early > 0.2, `the image changes while it accumulates (${early.toFixed(2)})`);
  assert.ok(late < 0.75 * early, `successive differences shrink: ${early.toFixed(2)} then ${late.toFixed(2)}`);

  // The cube fills the middle of the frame: its checker texture (orange and red) makes it red
  // dominant there, while the grey floor below is neutral.
  const pixel = (x: number, y: number): number[] => c.data.slice(4 * (y * width + x), 4 * (y * width + x) + 3);
  const [r, g, bl] = pixel(width / 2, height / 2);
  assert.ok(r! > 1.3 * g! && g! > bl!, `centre pixel ${[r, g, bl]} shows the orange/red texture`);
  const [fr, fg, fb] = pixel(width / 2, height - 3);
  assert.ok(Math.abs(fr! - fb!) < 0.15 * fr! && fg! > 20, `floor pixel ${[fr, fg, fb]} is grey`);

  await tab.locator('#viewport').screenshot({ path: join(ensureTestOutputDir(), 'demo-dropped-gltf.png') });
  assert.deepEqual(errors, []);
});
