// KHR material extensions through the whole glTF path: documents built with @gltf-transform/core,
// written as GLB, loaded by loadGltfScene and rendered on the GPU. The glass slab scene must give
// the same closed form as the hand-typed one (transmission-render.test.ts), so the loader's mapping
// of KHR_materials_transmission, _volume, _ior and _emissive_strength is checked by the image; the
// clearcoat and sheen swatches by their factors and by a white furnace (<= L, close to L).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { Document, type Buffer as GltfBuffer, type Material, type Mesh, type TypedArray } from '@gltf-transform/core';
import { KHRMaterialsClearcoat, KHRMaterialsEmissiveStrength, KHRMaterialsIOR, KHRMaterialsSheen, KHRMaterialsTransmission, KHRMaterialsVolume } from '@gltf-transform/extensions';
import type { WavefrontMaterialInput } from '../../src/scene/types.ts';
import { orthographicCameraNode, renderScene, roundTrip } from '../pathtracer/gltf-scenes.ts';
import { box, slabTransmittance } from './slab-scene.ts';

function mesh(doc: Document, buffer: GltfBuffer, geometry: { positions: number[]; indices: number[] }, material: Material): Mesh {
  const primitive = doc
    .createPrimitive()
    .setAttribute('POSITION', doc.createAccessor().setType('VEC3').setArray(new Float32Array(geometry.positions) as TypedArray).setBuffer(buffer))
    .setIndices(doc.createAccessor().setType('SCALAR').setArray(new Uint16Array(geometry.indices)).setBuffer(buffer))
    .setMaterial(material);
  return doc.createMesh().addPrimitive(primitive);
}

function materialOf(scene: { meshes?: readonly { material?: unknown }[]; materials?: readonly WavefrontMaterialInput[] }, name: string): WavefrontMaterialInput {
  const all = [...(scene.materials ?? []), ...(scene.meshes ?? []).map((m) => m.material).filter((m): m is WavefrontMaterialInput => typeof m === 'object' && m !== null)];
  const found = all.find((m) => m.name === name);
  assert.ok(found, `material ${name} in the loaded scene`);
  return found;
}

const E = [2, 3, 4];

test('glTF glass slab (KHR_materials_transmission + volume + ior) in front of an emissive_strength emitter matches Beer-Lambert and Fresnel', async () => {
  const doc = new Document();
  const buffer = doc.createBuffer();
  const color: [number, number, number] = [0.5, 0.7, 0.9];
  const thickness = 0.6;
  const distance = 0.8;
  const glass = doc.createMaterial('glass').setBaseColorFactor([1, 1, 1, 1]).setMetallicFactor(0).setRoughnessFactor(0)
    .setExtension('KHR_materials_transmission', doc.createExtension(KHRMaterialsTransmission).createTransmission().setTransmissionFactor(1))
    .setExtension('KHR_materials_volume', doc.createExtension(KHRMaterialsVolume).createVolume().setThicknessFactor(thickness).setAttenuationColor(color).setAttenuationDistance(distance))
    .setExtension('KHR_materials_ior', doc.createExtension(KHRMaterialsIOR).createIOR().setIOR(1.5));
  const light = doc.createMaterial('emitter').setBaseColorFactor([0, 0, 0, 1]).setMetallicFactor(0).setRoughnessFactor(1).setEmissiveFactor([E[0]! / 4, E[1]! / 4, E[2]! / 4])
    .setExtension('KHR_materials_emissive_strength', doc.createExtension(KHRMaterialsEmissiveStrength).createEmissiveStrength().setEmissiveStrength(4))
    .setExtension('KHR_materials_ior', doc.createExtension(KHRMaterialsIOR).createIOR().setIOR(1));
  const emitterQuad = { positions: [-4, -4, -2, 4, -4, -2, 4, 4, -2, -4, 4, -2], indices: [0, 1, 2, 0, 2, 3] };
  doc.createScene().addChild(doc.createNode('slab').setMesh(mesh(doc, buffer, box(-thickness / 2, thickness / 2), glass)))
    .addChild(doc.createNode('emitter').setMesh(mesh(doc, buffer, emitterQuad, light)))
    .addChild(orthographicCameraNode(doc, 1, [0, 0, 4]));
  const scene = await roundTrip(doc);
  const loaded = materialOf(scene, 'glass');
  assert.equal(loaded.transmissionFactor, 1);
  assert.equal(loaded.thicknessFactor, thickness);
  assert.equal(loaded.ior, 1.5);
  const size = 16;
  const { stats, radiance } = await renderScene(scene, { width: size, height: size, maxDepth: 24 }, 64);
  assert.equal(stats.invalidSamples, 0);
  for (let c = 0; c < 3; c++) {
    let mean = 0;
    for (let p = 0; p < size * size; p++) mean += radiance[4 * p + c]! / (size * size);
    const t = slabTransmittance(1.5, color[c]! ** (thickness / distance)) * E[c]!;
    assert.ok(Math.abs(mean - t) <= 0.01 * t, `channel ${c}: ${mean} vs ${t}`);
  }
});

test('glTF clearcoat and sheen swatches: factors load under their glTF names and a white furnace stays <= L and close to it', async () => {
  const doc = new Document();
  const buffer = doc.createBuffer();
  const coat = doc.createMaterial('coat').setBaseColorFactor([1, 1, 1, 1]).setMetallicFactor(0).setRoughnessFactor(0.9)
    .setExtension('KHR_materials_clearcoat', doc.createExtension(KHRMaterialsClearcoat).createClearcoat().setClearcoatFactor(1).setClearcoatRoughnessFactor(0.3));
  const velvet = doc.createMaterial('velvet').setBaseColorFactor([1, 1, 1, 1]).setMetallicFactor(0).setRoughnessFactor(1)
    .setExtension('KHR_materials_sheen', doc.createExtension(KHRMaterialsSheen).createSheen().setSheenColorFactor([1, 1, 1]).setSheenRoughnessFactor(0.4));
  // Two one-sided swatches facing the camera: everything they reflect escapes.
  const swatch = (x0: number): { positions: number[]; indices: number[] } => ({ positions: [x0, -1, 0, x0 + 1.9, -1, 0, x0 + 1.9, 1, 0, x0, 1, 0], indices: [0, 1, 2, 0, 2, 3] });
  doc.createScene().addChild(doc.createNode('coat').setMesh(mesh(doc, buffer, swatch(-2), coat)))
    .addChild(doc.createNode('velvet').setMesh(mesh(doc, buffer, swatch(0.1), velvet)))
    .addChild(orthographicCameraNode(doc, 2, [0, 0, 3]));
  const scene = await roundTrip(doc);
  const c = materialOf(scene, 'coat');
  assert.equal(c.clearcoatFactor, 1);
  assert.ok(Math.abs(c.clearcoatRoughnessFactor! - 0.3) < 1e-6);
  const v = materialOf(scene, 'velvet');
  assert.deepEqual(v.sheenColorFactor, [1, 1, 1]);
  assert.ok(Math.abs(v.sheenRoughnessFactor! - 0.4) < 1e-6);
  const width = 32;
  const height = 16;
  const L = 1.5;
  const { stats, radiance } = await renderScene(scene, { width, height, maxDepth: 8, environment: { color: [L, L, L] }, energyCompensation: true }, 64);
  assert.equal(stats.invalidSamples, 0);
  // Left half: the coat swatch, right half: the velvet one (away from the gap at x = 0).
  const mean = (x0: number, x1: number): number => {
    let s = 0;
    let n = 0;
    for (let y = 2; y < height - 2; y++) for (let x = x0; x < x1; x++) for (let k = 0; k < 3; k++) { s += radiance[4 * (y * width + x) + k]!; n++; }
    return s / n / L;
  };
  const coatRatio = mean(2, 14);
  const velvetRatio = mean(18, 30);
  assert.ok(coatRatio <= 1.01 && coatRatio >= 0.97, `clearcoat over white: ${coatRatio}`);
  assert.ok(velvetRatio <= 1.01 && velvetRatio >= 0.85, `sheen over white: ${velvetRatio}`);
});
