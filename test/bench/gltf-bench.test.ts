// The glTF benchmark's inputs: the generated assets are deterministic and load as described, and
// the "textures averaged" scene keeps each surface's mean reflectance.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { NodeIO } from '@gltf-transform/core';
import { ALL_EXTENSIONS } from '@gltf-transform/extensions';
import { terrainGlb, texturedRoomDocument } from '../../bench/gltf-assets.ts';
import { withTexturesAveraged } from '../../bench/gltf.ts';
import { loadGltfScene } from '../../src/io/index.ts';

test('terrainGlb: at least the requested triangles, unit normals, the same bytes every time', async () => {
  const a = await terrainGlb(5000, { textureSize: 64 });
  const b = await terrainGlb(5000, { textureSize: 64 });
  assert.ok(a.triangles >= 5000 && a.triangles < 5000 * 1.1, `${a.triangles} triangles`);
  assert.deepEqual(a.glb, b.glb, 'deterministic');
  const scene = await loadGltfScene(a.glb);
  assert.equal(scene.meshes.length, 1);
  const mesh = scene.meshes[0]!;
  assert.equal(mesh.indices!.length, 3 * a.triangles);
  assert.equal(mesh.positions.length, 3 * a.vertices);
  for (let v = 0; v < a.vertices; v += 97) {
    const n = Array.from(mesh.normals!).slice(3 * v, 3 * v + 3);
    assert.ok(Math.abs(Math.hypot(...n) - 1) < 1e-5 && n[1]! > 0, `normal ${v}: ${n}`);
  }
  // Every triangle faces up (+y), counter-clockwise seen from above.
  const p = mesh.positions;
  const ix = mesh.indices!;
  for (let t = 0; t < ix.length; t += 3 * 31) {
    const [i, j, k] = [ix[t]!, ix[t + 1]!, ix[t + 2]!];
    const e1 = [0, 1, 2].map((c) => p[3 * j + c]! - p[3 * i + c]!);
    const e2 = [0, 1, 2].map((c) => p[3 * k + c]! - p[3 * i + c]!);
    assert.ok(e1[2]! * e2[0]! - e1[0]! * e2[2]! > 0, `triangle ${t / 3} faces down`);
  }
  assert.deepEqual([scene.images[0]!.width, scene.images[0]!.height], [64, 64]);
});

test('the textured room loads with its textures, camera and emitter; averaging keeps mean reflectance', async () => {
  const glb = await new NodeIO().registerExtensions(ALL_EXTENSIONS).writeBinary(texturedRoomDocument());
  const scene = await loadGltfScene(glb);
  assert.equal(scene.camera.type, 'perspective');
  assert.equal(scene.images.length, 4);
  assert.ok(scene.materials.some((m) => m.emissiveFactor?.some((c) => c > 0)));
  const averaged = withTexturesAveraged(scene);
  assert.deepEqual([averaged.textures, averaged.images], [[], []]);
  for (const m of averaged.materials!) assert.ok(Object.keys(m).every((k) => !k.endsWith('Texture')), `${m.name} keeps a texture`);
  // An independent mean of the floor's base colour texture, decoded from sRGB texel by texel.
  const floorIndex = scene.materials.findIndex((m) => m.name === 'floor');
  const image = scene.images[scene.textures[scene.materials[floorIndex]!.baseColorTexture!.index]!.image as number]!;
  const decode = (b: number): number => (b / 255 <= 0.04045 ? b / 255 / 12.92 : ((b / 255 + 0.055) / 1.055) ** 2.4);
  let red = 0;
  for (let t = 0; t < image.width * image.height; t++) red += decode(image.data[4 * t]!) / (image.width * image.height);
  assert.ok(Math.abs(averaged.materials![floorIndex]!.baseColorFactor![0]! - red) < 1e-9);
});
