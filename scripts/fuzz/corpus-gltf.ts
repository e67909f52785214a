/**
 * The glTF seed corpus, built by code with @gltf-transform (no binary fixtures): small assets that
 * together reach every part of the loader: external and embedded buffers and images (PNG, JPEG,
 * WebP, KTX2 (ETC1S, UASTC) and AVIF), texture transforms and samplers, sparse accessors and morph targets,
 * quantised and strip/fan/restart geometry, deep hierarchies, GPU instancing, cameras, lights,
 * node visibility, every KHR_materials_* extension with textures, variants, skins and animations,
 * Draco and meshopt compression.
 */
import { Document, NodeIO, type Accessor, type Buffer as GltfBuffer, type Material, type TypedArray } from '@gltf-transform/core';
import {
  ALL_EXTENSIONS,
  EXTMeshGPUInstancing,
  EXTMeshoptCompression,
  EXTTextureAVIF,
  EXTTextureWebP,
  KHRDracoMeshCompression,
  KHRLightsPunctual,
  KHRMaterialsAnisotropy,
  KHRMaterialsClearcoat,
  KHRMaterialsDiffuseTransmission,
  KHRMaterialsDispersion,
  KHRMaterialsEmissiveStrength,
  KHRMaterialsIOR,
  KHRMaterialsIridescence,
  KHRMaterialsPBRSpecularGlossiness,
  KHRMaterialsSheen,
  KHRMaterialsSpecular,
  KHRMaterialsTransmission,
  KHRMaterialsUnlit,
  KHRMaterialsVariants,
  KHRMaterialsVolume,
  KHRMeshQuantization,
  KHRNodeVisibility,
  KHRTextureBasisu,
  KHRTextureTransform,
} from '@gltf-transform/extensions';
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { encode as encodePng } from 'fast-png';
import jpeg from 'jpeg-js';
import { MeshoptEncoder } from 'meshoptimizer';
import type { Json } from './mutate-json.ts';

/** A seed: glTF JSON whose buffers and images name resources by URI. */
export interface GltfSeed {
  name: string;
  json: Json;
  resources: Record<string, Uint8Array>;
}

const io = (dependencies: Record<string, unknown> = {}): NodeIO => new NodeIO().registerExtensions(ALL_EXTENSIONS).registerDependencies(dependencies);

function pixels(width: number, height: number): Uint8Array {
  const data = new Uint8Array(width * height * 4);
  for (let i = 0; i < data.length; i++) data[i] = (i * 37) & 0xff;
  return data;
}

const png = (w = 4, h = 4): Uint8Array => encodePng({ width: w, height: h, data: pixels(w, h), channels: 4 });
const png16 = (): Uint8Array => encodePng({ width: 3, height: 2, data: new Uint16Array(18).map((_, i) => i * 3000), channels: 3, depth: 16 });
const jpg = (): Uint8Array => new Uint8Array(jpeg.encode({ width: 8, height: 8, data: Buffer.from(pixels(8, 8)) }, 80).data);

async function webp(): Promise<Uint8Array> {
  const specifier = 'webp-wasm';
  const codec = (await import(specifier)) as { default: { encode(image: { width: number; height: number; data: Uint8ClampedArray }, options?: unknown): Promise<Uint8Array> } };
  return new Uint8Array(await codec.default.encode({ width: 4, height: 4, data: new Uint8ClampedArray(pixels(4, 4)) }, { quality: 80 }));
}

/** The codec fixtures of the glTF tests (32 x 32, made by test/io/gltf/fixtures/make-codec-fixtures.ts). */
const codecFixture = (name: string): Uint8Array => new Uint8Array(readFileSync(fileURLToPath(new URL(`../../test/io/gltf/fixtures/${name}`, import.meta.url))));

function attr(doc: Document, buffer: GltfBuffer, type: 'SCALAR' | 'VEC2' | 'VEC3' | 'VEC4', array: TypedArray, normalized = false): Accessor {
  return doc.createAccessor().setType(type).setArray(array).setBuffer(buffer).setNormalized(normalized);
}

function quad(doc: Document, buffer: GltfBuffer, material?: Material): ReturnType<Document['createMesh']> {
  const primitive = doc
    .createPrimitive()
    .setAttribute('POSITION', attr(doc, buffer, 'VEC3', new Float32Array([0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0])))
    .setAttribute('NORMAL', attr(doc, buffer, 'VEC3', new Float32Array([0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1])))
    .setAttribute('TEXCOORD_0', attr(doc, buffer, 'VEC2', new Float32Array([0, 1, 1, 1, 1, 0, 0, 0])))
    .setAttribute('COLOR_0', attr(doc, buffer, 'VEC4', new Uint8Array([255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255]), true))
    .setIndices(attr(doc, buffer, 'SCALAR', new Uint16Array([0, 1, 2, 0, 2, 3])));
  if (material) primitive.setMaterial(material);
  return doc.createMesh('quad').addPrimitive(primitive);
}

async function toSeed(name: string, doc: Document, dependencies: Record<string, unknown> = {}): Promise<GltfSeed> {
  const { json, resources } = await io(dependencies).writeJSON(doc);
  return { name, json: json as unknown as Json, resources: { ...resources } };
}

async function textured(): Promise<GltfSeed> {
  const doc = new Document();
  doc.createExtension(KHRTextureTransform);
  doc.createExtension(KHRLightsPunctual);
  const buffer = doc.createBuffer().setURI('asset.bin');
  const base = doc.createTexture('base').setMimeType('image/png').setImage(png()).setURI('tex.png');
  const normal = doc.createTexture('normal').setMimeType('image/jpeg').setImage(jpg()).setURI('normal.jpg');
  const deep = doc.createTexture('deep').setMimeType('image/png').setImage(png16()).setURI('sub/deep.png');
  const transform = doc.createExtension(KHRTextureTransform).createTransform().setOffset([0.25, 0]).setRotation(0.5).setScale([2, 2]);
  const material = doc.createMaterial('textured').setBaseColorTexture(base).setNormalTexture(normal).setOcclusionTexture(deep).setAlphaMode('MASK').setAlphaCutoff(0.3);
  material.getBaseColorTextureInfo()!.setWrapS(33648).setMagFilter(9728).setMinFilter(9987).setExtension('KHR_texture_transform', transform);
  const camera = doc.createCamera('cam').setType('perspective').setYFov(0.8).setZNear(0.01).setZFar(100).setAspectRatio(1.5);
  const light = doc.createExtension(KHRLightsPunctual).createLight('lamp').setType('point').setIntensity(5).setColor([1, 0.9, 0.8]).setRange(10);
  doc.createScene('main')
    .addChild(doc.createNode('quad').setMesh(quad(doc, buffer, material)))
    .addChild(doc.createNode('camera').setCamera(camera).setTranslation([0.5, 0.5, 3]))
    .addChild(doc.createNode('light').setExtension('KHR_lights_punctual', light).setTranslation([0, 2, 2]));
  return toSeed('textured', doc);
}

async function embedded(): Promise<GltfSeed> {
  const doc = new Document();
  doc.createExtension(EXTTextureWebP).setRequired(false);
  const buffer = doc.createBuffer();
  const tex = doc.createTexture('webp').setMimeType('image/webp').setImage(await webp());
  const jpgTex = doc.createTexture('jpg').setMimeType('image/jpeg').setImage(jpg());
  const material = doc.createMaterial('embedded').setBaseColorTexture(tex).setEmissiveTexture(jpgTex).setEmissiveFactor([0.5, 0.5, 0.5]).setDoubleSided(true);
  doc.createScene().addChild(doc.createNode('n').setMesh(quad(doc, buffer, material)));
  // One buffer, images in buffer views: the layout of a .glb.
  const { json, resources } = await io().writeJSON(doc, { format: 'GLB' } as never);
  return { name: 'embedded', json: json as unknown as Json, resources: { ...resources } };
}

async function sparseMorph(): Promise<GltfSeed> {
  const doc = new Document();
  const buffer = doc.createBuffer().setURI('asset.bin');
  const base = quad(doc, buffer);
  const primitive = base.listPrimitives()[0]!;
  const delta = attr(doc, buffer, 'VEC3', new Float32Array([0, 0, 0, 0, 0, 0, 0, 0, 0.5, 0, 0, 0])).setSparse(true);
  primitive.addTarget(doc.createPrimitiveTarget().setAttribute('POSITION', delta));
  base.setWeights([0.5]);
  primitive.setIndices(attr(doc, buffer, 'SCALAR', new Uint8Array([0, 1, 2, 0, 2, 3])));
  doc.createScene().addChild(doc.createNode('morphed').setMesh(base).setWeights([0.75]));
  return toSeed('sparse-morph', doc);
}

async function hierarchy(): Promise<GltfSeed> {
  const doc = new Document();
  doc.createExtension(KHRNodeVisibility);
  const instancing = doc.createExtension(EXTMeshGPUInstancing);
  const lights = doc.createExtension(KHRLightsPunctual);
  const buffer = doc.createBuffer().setURI('asset.bin');
  const mesh = quad(doc, buffer);
  let parent = doc.createNode('root').setTranslation([0, 1, 0]);
  const scene = doc.createScene('chain').addChild(parent);
  for (let i = 0; i < 30; i++) {
    const child = doc.createNode(`n${i}`).setTranslation([0.1, 0, 0]).setRotation([0, 0, Math.sin(0.05), Math.cos(0.05)]).setScale([1.01, 1, 1]);
    if (i % 5 === 0) child.setMesh(mesh);
    parent.addChild(child);
    parent = child;
  }
  const batch = instancing
    .createInstancedMesh()
    .setAttribute('TRANSLATION', attr(doc, buffer, 'VEC3', new Float32Array([0, 0, 0, 2, 0, 0, 4, 0, 0])))
    .setAttribute('SCALE', attr(doc, buffer, 'VEC3', new Float32Array([1, 1, 1, 2, 2, 2, 0.5, 0.5, 0.5])));
  scene.addChild(doc.createNode('instanced').setMesh(mesh).setExtension('EXT_mesh_gpu_instancing', batch));
  scene.addChild(doc.createNode('hidden').setMesh(mesh).setExtension('KHR_node_visibility', doc.createExtension(KHRNodeVisibility).createVisibility().setVisible(false)));
  scene.addChild(doc.createNode('ortho').setCamera(doc.createCamera('o').setType('orthographic').setXMag(2).setYMag(2).setZNear(0.1).setZFar(50)).setMatrix([1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 5, 1]));
  scene.addChild(doc.createNode('spot').setExtension('KHR_lights_punctual', lights.createLight('s').setType('spot').setInnerConeAngle(0.2).setOuterConeAngle(0.6).setIntensity(10)).setTranslation([0, 3, 0]));
  scene.addChild(doc.createNode('sun').setExtension('KHR_lights_punctual', lights.createLight('d').setType('directional').setIntensity(2)));
  doc.createScene('other').addChild(doc.createNode('alone').setMesh(mesh));
  doc.getRoot().setDefaultScene(scene);
  return toSeed('hierarchy', doc);
}

async function materials(): Promise<GltfSeed> {
  const doc = new Document();
  const buffer = doc.createBuffer();
  const t = (): ReturnType<Document['createTexture']> => doc.createTexture().setMimeType('image/png').setImage(png(2, 2));
  const m = doc.createMaterial('everything').setBaseColorFactor([0.8, 0.6, 0.4, 1]).setMetallicFactor(0.3).setRoughnessFactor(0.4).setMetallicRoughnessTexture(t());
  m.setExtension('KHR_materials_emissive_strength', doc.createExtension(KHRMaterialsEmissiveStrength).createEmissiveStrength().setEmissiveStrength(3));
  m.setExtension('KHR_materials_ior', doc.createExtension(KHRMaterialsIOR).createIOR().setIOR(1.4));
  m.setExtension('KHR_materials_specular', doc.createExtension(KHRMaterialsSpecular).createSpecular().setSpecularFactor(0.7).setSpecularColorFactor([1, 0.9, 0.8]).setSpecularTexture(t()));
  m.setExtension('KHR_materials_transmission', doc.createExtension(KHRMaterialsTransmission).createTransmission().setTransmissionFactor(0.5).setTransmissionTexture(t()));
  m.setExtension('KHR_materials_volume', doc.createExtension(KHRMaterialsVolume).createVolume().setThicknessFactor(0.2).setAttenuationDistance(2).setAttenuationColor([0.9, 0.5, 0.5]));
  m.setExtension('KHR_materials_clearcoat', doc.createExtension(KHRMaterialsClearcoat).createClearcoat().setClearcoatFactor(0.5).setClearcoatRoughnessFactor(0.2).setClearcoatNormalTexture(t()));
  m.setExtension('KHR_materials_sheen', doc.createExtension(KHRMaterialsSheen).createSheen().setSheenColorFactor([0.5, 0.5, 1]).setSheenRoughnessFactor(0.5));
  m.setExtension('KHR_materials_dispersion', doc.createExtension(KHRMaterialsDispersion).createDispersion().setDispersion(0.3));
  m.setExtension('KHR_materials_iridescence', doc.createExtension(KHRMaterialsIridescence).createIridescence().setIridescenceFactor(0.6).setIridescenceIOR(1.3).setIridescenceThicknessMinimum(100).setIridescenceThicknessMaximum(400));
  m.setExtension('KHR_materials_anisotropy', doc.createExtension(KHRMaterialsAnisotropy).createAnisotropy().setAnisotropyStrength(0.5).setAnisotropyRotation(0.3).setAnisotropyTexture(t()));
  m.setExtension('KHR_materials_diffuse_transmission', doc.createExtension(KHRMaterialsDiffuseTransmission).createDiffuseTransmission().setDiffuseTransmissionFactor(0.3).setDiffuseTransmissionColorFactor([1, 0.8, 0.6]));
  const unlit = doc.createMaterial('unlit').setExtension('KHR_materials_unlit', doc.createExtension(KHRMaterialsUnlit).createUnlit());
  const sg = doc.createMaterial('specgloss').setExtension('KHR_materials_pbrSpecularGlossiness', doc.createExtension(KHRMaterialsPBRSpecularGlossiness).createPBRSpecularGlossiness().setDiffuseFactor([0.5, 0.5, 0.5, 1]).setGlossinessFactor(0.6));
  const variantsExt = doc.createExtension(KHRMaterialsVariants);
  const day = variantsExt.createVariant('Day');
  const night = variantsExt.createVariant('Night');
  const mesh = quad(doc, buffer, m);
  const mapping = variantsExt.createMappingList().addMapping(variantsExt.createMapping().setMaterial(unlit).addVariant(night)).addMapping(variantsExt.createMapping().setMaterial(sg).addVariant(day));
  mesh.listPrimitives()[0]!.setExtension('KHR_materials_variants', mapping);
  doc.createScene().addChild(doc.createNode('m').setMesh(mesh));
  return toSeed('materials', doc);
}

async function skinned(): Promise<GltfSeed> {
  const doc = new Document();
  const buffer = doc.createBuffer().setURI('asset.bin');
  const mesh = quad(doc, buffer);
  const primitive = mesh.listPrimitives()[0]!;
  primitive.setAttribute('JOINTS_0', attr(doc, buffer, 'VEC4', new Uint8Array([0, 1, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0])));
  primitive.setAttribute('WEIGHTS_0', attr(doc, buffer, 'VEC4', new Float32Array([1, 0, 0, 0, 0.5, 0.5, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0])));
  const hip = doc.createNode('hip');
  const knee = doc.createNode('knee').setTranslation([0, 1, 0]);
  hip.addChild(knee);
  const skin = doc.createSkin('skin').addJoint(hip).addJoint(knee).setInverseBindMatrices(attr(doc, buffer, 'MAT4' as never, new Float32Array([1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1])));
  const input = attr(doc, buffer, 'SCALAR', new Float32Array([0, 0.5, 1]));
  const output = attr(doc, buffer, 'VEC4', new Float32Array([0, 0, 0, 1, 0, 0, 0.2, 0.98, 0, 0, 0, 1]));
  const sampler = doc.createAnimationSampler().setInput(input).setOutput(output).setInterpolation('LINEAR');
  doc.createAnimation('bend').addSampler(sampler).addChannel(doc.createAnimationChannel().setTargetNode(knee).setTargetPath('rotation').setSampler(sampler));
  doc.createScene().addChild(hip).addChild(doc.createNode('skinned').setMesh(mesh).setSkin(skin));
  return toSeed('skinned', doc);
}

async function compressed(): Promise<GltfSeed[]> {
  const specifier = 'draco3dgltf';
  const draco3d = ((await import(specifier)) as { default: { createEncoderModule(): Promise<unknown> } }).default;
  const dracoDoc = new Document();
  dracoDoc.createExtension(KHRDracoMeshCompression).setRequired(true);
  dracoDoc.createScene().addChild(dracoDoc.createNode('d').setMesh(quad(dracoDoc, dracoDoc.createBuffer())));
  const draco = await toSeed('draco', dracoDoc, { 'draco3d.encoder': await draco3d.createEncoderModule() });
  await MeshoptEncoder.ready;
  const meshoptDoc = new Document();
  meshoptDoc.createExtension(EXTMeshoptCompression).setRequired(true).setEncoderOptions({ method: EXTMeshoptCompression.EncoderMethod.FILTER });
  meshoptDoc.createScene().addChild(meshoptDoc.createNode('m').setMesh(quad(meshoptDoc, meshoptDoc.createBuffer())));
  const meshopt = await toSeed('meshopt', meshoptDoc, { 'meshopt.encoder': MeshoptEncoder });
  return [draco, meshopt];
}

async function topology(): Promise<GltfSeed> {
  const doc = new Document();
  doc.createExtension(KHRMeshQuantization).setRequired(true);
  const buffer = doc.createBuffer().setURI('asset.bin');
  const positions = attr(doc, buffer, 'VEC3', new Int16Array([0, 0, 0, 100, 0, 0, 0, 100, 0, 100, 100, 0]));
  const strip = doc.createPrimitive().setMode(5).setAttribute('POSITION', positions).setIndices(attr(doc, buffer, 'SCALAR', new Uint32Array([0, 1, 2, 3])));
  const fan = doc.createPrimitive().setMode(6).setAttribute('POSITION', positions);
  const lines = doc.createPrimitive().setMode(1).setAttribute('POSITION', positions);
  const uvs = doc.createPrimitive().setAttribute('POSITION', positions).setAttribute('TEXCOORD_0', attr(doc, buffer, 'VEC2', new Uint16Array([0, 0, 65535, 0, 0, 65535, 65535, 65535]), true)).setIndices(attr(doc, buffer, 'SCALAR', new Uint8Array([0, 1, 2, 1, 3, 2])));
  const mesh = doc.createMesh('topology').addPrimitive(strip).addPrimitive(fan).addPrimitive(lines).addPrimitive(uvs);
  doc.createScene().addChild(doc.createNode('t').setMesh(mesh).setScale([0.01, 0.01, 0.01]));
  return toSeed('topology', doc);
}

async function fallbacks(): Promise<GltfSeed> {
  const doc = new Document();
  doc.createExtension(KHRTextureBasisu).setRequired(false);
  doc.createExtension(EXTTextureAVIF).setRequired(false);
  const buffer = doc.createBuffer().setURI('asset.bin');
  const ktx = doc.createTexture('gpu').setMimeType('image/ktx2').setImage(codecFixture('pattern-etc1s.ktx2')).setURI('tex.ktx2');
  const uastc = doc.createTexture('uastc').setMimeType('image/ktx2').setImage(codecFixture('pattern-uastc.ktx2')).setURI('sub/uastc.ktx2');
  const avif = doc.createTexture('avif').setMimeType('image/avif').setImage(codecFixture('pattern.avif')).setURI('tex.avif');
  const material = doc.createMaterial('k').setBaseColorTexture(ktx).setNormalTexture(uastc).setEmissiveTexture(avif).setEmissiveFactor([1, 1, 1]);
  doc.createScene().addChild(doc.createNode('k').setMesh(quad(doc, buffer, material)));
  const seed = await toSeed('fallbacks', doc);
  // Exporters write an optional basisu texture with a core PNG source as fallback.
  const json = seed.json as { images: Json[]; textures: Array<Record<string, Json>> };
  json.textures[0]!.source = json.images.push({ uri: 'fallback.png', mimeType: 'image/png' }) - 1;
  seed.resources['fallback.png'] = png();
  return seed;
}

/** A one-triangle asset written by hand, its buffer a data URI. */
function minimal(): GltfSeed {
  const positions = new Float32Array([0, 0, 0, 1, 0, 0, 0, 1, 0]);
  const base64 = Buffer.from(positions.buffer).toString('base64');
  return {
    name: 'minimal',
    json: {
      asset: { version: '2.0' },
      buffers: [{ uri: `data:application/octet-stream;base64,${base64}`, byteLength: 36 }],
      bufferViews: [{ buffer: 0, byteLength: 36 }],
      accessors: [{ bufferView: 0, componentType: 5126, count: 3, type: 'VEC3', min: [0, 0, 0], max: [1, 1, 0] }],
      meshes: [{ primitives: [{ attributes: { POSITION: 0 } }] }],
      nodes: [{ mesh: 0 }],
      scenes: [{ nodes: [0] }],
      scene: 0,
    },
    resources: {},
  };
}

export async function buildGltfCorpus(): Promise<GltfSeed[]> {
  return [await textured(), await embedded(), await sparseMorph(), await hierarchy(), await materials(), await skinned(), ...(await compressed()), await topology(), await fallbacks(), minimal()];
}
