import { test } from 'node:test';
import assert from 'node:assert/strict';
import { Document, TextureInfo } from '@gltf-transform/core';
import {
  KHRMaterialsAnisotropy,
  KHRMaterialsClearcoat,
  KHRMaterialsDiffuseTransmission,
  KHRMaterialsDispersion,
  KHRMaterialsEmissiveStrength,
  KHRMaterialsIOR,
  KHRMaterialsIridescence,
  KHRMaterialsSheen,
  KHRMaterialsSpecular,
  KHRMaterialsTransmission,
  KHRMaterialsVolume,
  KHRMaterialsPBRSpecularGlossiness,
  KHRMaterialsUnlit,
  KHRTextureTransform,
  EXTTextureWebP,
} from '@gltf-transform/extensions';
import { encode as encodePng } from 'fast-png';
import jpeg from 'jpeg-js';
import webp from 'webp-wasm';
import { loadGltfScene } from '../../../src/io/index.ts';
import { assertClose, quadMesh, toGlb, toGltfJsonBytes } from './helpers.ts';

/** 2x2 RGBA: top-left red, top-right green, bottom-left blue, bottom-right half-transparent white. */
const PIXELS = new Uint8Array([255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 128]);

function png(data = PIXELS, width = 2, height = 2): Uint8Array {
  return encodePng({ width, height, data, channels: 4, depth: 8 });
}

test('textured planes: slots, sampler state, KHR_texture_transform, shared images decoded once', async () => {
  const doc = new Document();
  const transformExt = doc.createExtension(KHRTextureTransform);
  const image = doc.createTexture('checker').setMimeType('image/png').setImage(png());
  const material = doc.createMaterial('plane').setBaseColorTexture(image).setEmissiveTexture(image).setEmissiveFactor([1, 1, 1]);
  material.getBaseColorTextureInfo()!
    .setWrapS(TextureInfo.WrapMode.CLAMP_TO_EDGE)
    .setWrapT(TextureInfo.WrapMode.MIRRORED_REPEAT)
    .setMagFilter(TextureInfo.MagFilter.NEAREST)
    .setMinFilter(TextureInfo.MinFilter.LINEAR_MIPMAP_NEAREST)
    .setTexCoord(1)
    .setExtension('KHR_texture_transform', transformExt.createTransform().setOffset([0.5, 0.25]).setRotation(0.3).setScale([2, 3]).setTexCoord(0));
  doc.createScene().addChild(doc.createNode('p').setMesh(quadMesh(doc, doc.createBuffer(), material)));
  const scene = await loadGltfScene(await toGlb(doc));

  assert.equal(scene.images.length, 1, 'one image, decoded once');
  assert.deepEqual([scene.images[0].width, scene.images[0].height], [2, 2]);
  assert.deepEqual([...scene.images[0].data], [...PIXELS], 'RGBA8, top row first');
  assert.equal(scene.textures.length, 2, 'two sampler states over the same image');
  assert.deepEqual(scene.textures[0], { name: 'checker', image: 0, sampler: { wrapS: 'clamp-to-edge', wrapT: 'mirrored-repeat', magFilter: 'nearest', minFilter: 'linear-mipmap-nearest' } });
  assert.deepEqual(scene.textures[1], { name: 'checker', image: 0, sampler: { wrapS: 'repeat', wrapT: 'repeat' } });
  const m = scene.materials[0];
  assert.equal(m.baseColorTexture!.index, 0);
  assert.equal(m.baseColorTexture!.texCoord, 1);
  const t = m.baseColorTexture!.transform!;
  assertClose(t.offset!, [0.5, 0.25], 1e-7, 'offset');
  assert.ok(Math.abs(t.rotation! - 0.3) < 1e-7);
  assertClose(t.scale!, [2, 3], 0, 'scale');
  assert.equal(t.texCoord, 0);
  assert.deepEqual(m.emissiveTexture, { index: 1, texCoord: 0 });
  assert.deepEqual(m.emissiveFactor, [1, 1, 1]);
});

test('PNG, JPEG and WebP images decode to RGBA8 in Node; 16-bit PNG is rounded to 8 bits', async () => {
  const doc = new Document();
  doc.createExtension(EXTTextureWebP);
  const buffer = doc.createBuffer();
  // JPEG: 16x16 flat colour blocks survive lossy coding within a few levels.
  const jw = 16;
  const jdata = new Uint8Array(jw * jw * 4);
  for (let p = 0; p < jw * jw; p++) jdata.set((p % jw) < 8 ? [200, 40, 30, 255] : [20, 90, 220, 255], p * 4);
  const jpegBytes = new Uint8Array(jpeg.encode({ width: jw, height: jw, data: jdata }, 95).data);
  const webpBytes = new Uint8Array(await webp.encode({ data: new Uint8ClampedArray(PIXELS), width: 2, height: 2 }, { lossless: 1, exact: 1 }));
  const deep = encodePng({ width: 1, height: 2, data: new Uint16Array([65535, 0, 257, 65535, 0, 32896, 65535, 0]), channels: 4, depth: 16 });
  const textures = [
    doc.createTexture('png').setMimeType('image/png').setImage(png()),
    doc.createTexture('jpeg').setMimeType('image/jpeg').setImage(jpegBytes),
    doc.createTexture('webp').setMimeType('image/webp').setImage(webpBytes),
    doc.createTexture('deep').setMimeType('image/png').setImage(deep),
  ];
  const node = doc.createScene();
  textures.forEach((tex, i) => node.addChild(doc.createNode(`n${i}`).setMesh(quadMesh(doc, buffer, doc.createMaterial(`m${i}`).setBaseColorTexture(tex)))));
  const scene = await loadGltfScene(await toGltfJsonBytes(doc));
  assert.equal(scene.images.length, 4);
  const [p, j, w, d] = scene.images;
  assert.deepEqual([...p.data], [...PIXELS]);
  assert.deepEqual([j.width, j.height], [16, 16]);
  for (let y = 0; y < jw; y++) {
    assertClose(j.data.slice((y * jw + 2) * 4, (y * jw + 2) * 4 + 4), [200, 40, 30, 255], 6, `jpeg left row ${y}`);
    assertClose(j.data.slice((y * jw + 13) * 4, (y * jw + 13) * 4 + 4), [20, 90, 220, 255], 6, `jpeg right row ${y}`);
  }
  assert.deepEqual([...w.data], [...PIXELS], 'lossless WebP decodes exactly');
  assert.deepEqual([...d.data], [255, 0, 1, 255, 0, 128, 255, 0]);
  assert.deepEqual(scene.warnings, []);
});

test('KHR_materials_* factors and textures under their glTF names', async () => {
  const doc = new Document();
  const tex = doc.createTexture('t').setMimeType('image/png').setImage(png());
  const m = doc.createMaterial('all').setAlphaMode('MASK').setAlphaCutoff(0.3).setDoubleSided(true).setMetallicFactor(0.2).setRoughnessFactor(0.7);
  m.setExtension('KHR_materials_ior', doc.createExtension(KHRMaterialsIOR).createIOR().setIOR(1.33));
  m.setExtension('KHR_materials_emissive_strength', doc.createExtension(KHRMaterialsEmissiveStrength).createEmissiveStrength().setEmissiveStrength(5));
  m.setExtension('KHR_materials_specular', doc.createExtension(KHRMaterialsSpecular).createSpecular().setSpecularFactor(0.4).setSpecularColorFactor([1, 0.5, 0.2]).setSpecularColorTexture(tex));
  m.setExtension('KHR_materials_transmission', doc.createExtension(KHRMaterialsTransmission).createTransmission().setTransmissionFactor(0.9).setTransmissionTexture(tex));
  m.setExtension('KHR_materials_volume', doc.createExtension(KHRMaterialsVolume).createVolume().setThicknessFactor(0.1).setAttenuationColor([0.9, 0.8, 0.7]).setAttenuationDistance(2));
  m.setExtension('KHR_materials_clearcoat', doc.createExtension(KHRMaterialsClearcoat).createClearcoat().setClearcoatFactor(1).setClearcoatRoughnessFactor(0.05).setClearcoatNormalTexture(tex).setClearcoatNormalScale(0.8));
  m.setExtension('KHR_materials_sheen', doc.createExtension(KHRMaterialsSheen).createSheen().setSheenColorFactor([0.3, 0.2, 0.1]).setSheenRoughnessFactor(0.6));
  m.setExtension('KHR_materials_dispersion', doc.createExtension(KHRMaterialsDispersion).createDispersion().setDispersion(0.25));
  m.setExtension('KHR_materials_anisotropy', doc.createExtension(KHRMaterialsAnisotropy).createAnisotropy().setAnisotropyStrength(0.5).setAnisotropyRotation(1.2));
  m.setExtension('KHR_materials_iridescence', doc.createExtension(KHRMaterialsIridescence).createIridescence().setIridescenceFactor(1).setIridescenceIOR(1.4).setIridescenceThicknessMinimum(150).setIridescenceThicknessMaximum(500));
  m.setExtension('KHR_materials_diffuse_transmission', doc.createExtension(KHRMaterialsDiffuseTransmission).createDiffuseTransmission().setDiffuseTransmissionFactor(0.4).setDiffuseTransmissionColorFactor([1, 0.9, 0.8]));
  doc.createScene().addChild(doc.createNode('n').setMesh(quadMesh(doc, doc.createBuffer(), m)));
  const scene = await loadGltfScene(await toGlb(doc));
  const out = scene.materials[0];
  const near = (a: number | undefined, b: number): boolean => a !== undefined && Math.abs(a - b) < 1e-6;
  assert.equal(out.alphaMode, 'MASK');
  assert.ok(near(out.alphaCutoff, 0.3) && near(out.metallicFactor, 0.2) && near(out.roughnessFactor, 0.7));
  assert.equal(out.doubleSided, true);
  assert.ok(near(out.ior, 1.33) && near(out.emissiveStrength, 5));
  assert.ok(near(out.specularFactor, 0.4));
  assertClose(out.specularColorFactor!, [1, 0.5, 0.2], 1e-6);
  assert.equal(out.specularColorTexture!.index, 0);
  assert.ok(near(out.transmissionFactor, 0.9) && out.transmissionTexture !== undefined);
  assert.ok(near(out.thicknessFactor, 0.1) && near(out.attenuationDistance, 2));
  assertClose(out.attenuationColor!, [0.9, 0.8, 0.7], 1e-6);
  assert.ok(near(out.clearcoatFactor, 1) && near(out.clearcoatRoughnessFactor, 0.05));
  assert.ok(near(out.clearcoatNormalTexture!.scale, 0.8));
  assertClose(out.sheenColorFactor!, [0.3, 0.2, 0.1], 1e-6);
  assert.ok(near(out.sheenRoughnessFactor, 0.6) && near(out.dispersion, 0.25));
  assert.ok(near(out.anisotropyStrength, 0.5) && near(out.anisotropyRotation, 1.2));
  assert.ok(near(out.iridescenceFactor, 1) && near(out.iridescenceIor, 1.4) && near(out.iridescenceThicknessMinimum, 150) && near(out.iridescenceThicknessMaximum, 500));
  assert.ok(near(out.diffuseTransmissionFactor, 0.4));
  assertClose(out.diffuseTransmissionColorFactor!, [1, 0.9, 0.8], 1e-6);
  // The clearcoat normal map and anisotropy need tangents: generated (the quad has none).
  assert.equal(scene.meshes[0].tangents!.length, 16);
});


test('KHR_materials_pbrSpecularGlossiness (required): a dielectric with the specular colour as F0 (ior 0) and roughness 1 - glossiness per texel', async () => {
  const doc = new Document();
  const ext = doc.createExtension(KHRMaterialsPBRSpecularGlossiness).setRequired(true);
  // Specular-glossiness texels: rgb specular colour, alpha glossiness 0, 128 and 255.
  const sg = doc.createTexture('sg').setMimeType('image/png').setImage(png(new Uint8Array([10, 20, 30, 0, 40, 50, 60, 128, 70, 80, 90, 255, 0, 0, 0, 255])));
  const diffuse = doc.createTexture('diffuse').setMimeType('image/png').setImage(png());
  const textured = doc.createMaterial('textured').setBaseColorFactor([1, 0, 1, 1]).setMetallicFactor(1);
  textured.setExtension('KHR_materials_pbrSpecularGlossiness', ext.createPBRSpecularGlossiness()
    .setDiffuseFactor([0.5, 0.6, 0.7, 0.8]).setDiffuseTexture(diffuse).setSpecularFactor([0.9, 0.8, 0.7]).setGlossinessFactor(0.5).setSpecularGlossinessTexture(sg));
  const plain = doc.createMaterial('factors only');
  plain.setExtension('KHR_materials_pbrSpecularGlossiness', ext.createPBRSpecularGlossiness().setDiffuseFactor([0.2, 0.3, 0.4, 1]).setSpecularFactor([0.04, 0.04, 0.04]).setGlossinessFactor(0.75));
  const buffer = doc.createBuffer();
  doc.createScene().addChild(doc.createNode('a').setMesh(quadMesh(doc, buffer, textured))).addChild(doc.createNode('b').setMesh(quadMesh(doc, buffer, plain)));
  const scene = await loadGltfScene(await toGlb(doc));
  assert.deepEqual(scene.warnings, []);
  const [m, f] = scene.materials;
  assertClose(m.baseColorFactor!, [0.5, 0.6, 0.7, 0.8], 1e-6, 'diffuse factor -> base colour factor');
  assert.deepEqual([...scene.images[scene.textures[m.baseColorTexture!.index].image as number].data], [...PIXELS], 'the diffuse texture is the base colour texture');
  assert.deepEqual([m.metallicFactor, m.roughnessFactor, m.ior, m.specularFactor], [0, 1, 0, 1]);
  assertClose(m.specularColorFactor!, [0.9, 0.8, 0.7], 1e-6, 'specular factor -> F0 colour');
  const specular = scene.images[scene.textures[m.specularColorTexture!.index].image as number];
  assert.equal(specular.data[4], 40, 'the specular-glossiness texture is the specular colour texture');
  const roughness = scene.images[scene.textures[m.metallicRoughnessTexture!.index].image as number];
  // G = 255 (1 - 0.5 alpha / 255); B (metallic) = 0.
  assert.deepEqual([0, 1, 2, 3].map((p) => roughness.data[p * 4 + 1]), [255, Math.round(255 * (1 - (0.5 * 128) / 255)), 128, 128]);
  assert.deepEqual([0, 1, 2, 3].map((p) => roughness.data[p * 4 + 2]), [0, 0, 0, 0]);
  assertClose(f.baseColorFactor!, [0.2, 0.3, 0.4, 1], 1e-6);
  assert.ok(Math.abs(f.roughnessFactor! - 0.25) < 1e-6 && f.metallicRoughnessTexture === undefined && f.metallicFactor === 0 && f.ior === 0);
});

test('KHR_materials_unlit (required): the base colour becomes emission and nothing scatters', async () => {
  const doc = new Document();
  const unlit = doc.createExtension(KHRMaterialsUnlit).setRequired(true);
  const image = doc.createTexture('colour').setMimeType('image/png').setImage(png());
  const material = doc.createMaterial('flat').setBaseColorFactor([0.25, 0.5, 1, 0.5]).setBaseColorTexture(image).setAlphaMode('BLEND').setExtension('KHR_materials_unlit', unlit.createUnlit());
  doc.createScene().addChild(doc.createNode('n').setMesh(quadMesh(doc, doc.createBuffer(), material)));
  const scene = await loadGltfScene(await toGlb(doc));
  assert.deepEqual(scene.warnings, []);
  const m = scene.materials[0];
  assertClose(m.emissiveFactor!, [0.25, 0.5, 1], 1e-6, 'emission = base colour factor');
  assert.equal(m.emissiveTexture!.index, m.baseColorTexture!.index, 'emission texture = base colour texture');
  assert.deepEqual([...m.baseColorFactor!], [0, 0, 0, 0.5], 'black base colour keeps the alpha');
  assert.deepEqual([m.emissiveStrength, m.metallicFactor, m.specularFactor, m.alphaMode], [1, 0, 0, 'BLEND']);
});
