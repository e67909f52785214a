// KHR_materials_unlit on the GPU: an unlit quad filling an orthographic view under a bright uniform
// environment (radiance 3) must show exactly its base colour: it emits that colour and reflects
// nothing. Shaded as PBR instead it would reflect the environment (several times the base colour).
// Emission seen directly carries no sampling noise, so every pixel is compared at f32 precision.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { Document } from '@gltf-transform/core';
import { KHRMaterialsUnlit } from '@gltf-transform/extensions';
import { orthographicCameraNode, quad, renderScene, roundTrip } from './gltf-scenes.ts';

test('an unlit surface shows its base colour under any light: emission, no scattering', async () => {
  const doc = new Document();
  const unlit = doc.createExtension(KHRMaterialsUnlit).setRequired(true);
  const base = [0.2, 0.5, 0.8] as const;
  const material = doc.createMaterial('unlit').setBaseColorFactor([...base, 1]).setExtension('KHR_materials_unlit', unlit.createUnlit());
  doc.createScene().addChild(orthographicCameraNode(doc, 2)).addChild(doc.createNode('quad').setMesh(quad(doc, doc.createBuffer(), material, { x0: -2, y0: -2, x1: 2, y1: 2, normals: true })));
  const scene = await roundTrip(doc);
  const { radiance, stats } = await renderScene(scene, { width: 8, height: 8, environment: { color: [3, 3, 3] } }, 4);
  assert.equal(stats.invalidSamples, 0);
  for (let p = 0; p < 64; p++) {
    for (let c = 0; c < 3; c++) assert.ok(Math.abs(radiance[p * 4 + c]! - base[c]!) < 1e-5, `pixel ${p} channel ${c}: ${radiance[p * 4 + c]} vs ${base[c]}`);
  }
});
