// Textured glTF planes end to end: assets built with @gltf-transform/core, read by loadGltfScene,
// rendered on the GPU, and compared with the CPU reference sampler (reference-sampler.ts) on the
// same atlas. Covers each wrap mode, KHR_texture_transform (offset, rotation, scale, texCoord
// override), both uv sets, nearest and linear filters, COLOR_0 and the base colour factor, then the
// emissive, normal and metallic-roughness slots, and the occlusion texture that the path tracer
// loads but does not apply.
//
// How the first-hit albedo AOV can be compared exactly: the orthographic camera's pixels are 1/8
// unit wide and each plane is 2 units (16 pixels) across, and the transforms below are chosen so
// that every texel edge (nearest) and every texel-centre line (linear: the edges of the bilinear
// cells) falls on a pixel edge. A pixel then sees one texel, or one bilinear cell, whose mean over
// the pixel equals the reference at the pixel centre (a bilinear function's mean over a rectangle
// is its value at the centre). The AOV averages jittered samples (Owen-scrambled Sobol points), so
// a pixel over a non-constant cell carries a quadrature error: measured up to 7e-4 (linear filter)
// and 2e-3 (with the COLOR_0 gradient) at 64 samples, against tolerances of 2e-3 and 5e-3, while a
// wrong texel, wrap or uv set moves some channel by at least 0.028 (any two of these texels differ
// by that much in linear light). Nearest filtering is constant over each pixel: only f32 rounding
// is left (1e-6), against 1e-4.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { Document, TextureInfo, type GLTF, type Material } from '@gltf-transform/core';
import { KHRMaterialsEmissiveStrength, KHRMaterialsIOR, KHRTextureTransform } from '@gltf-transform/extensions';
import { encode as encodePng } from 'fast-png';
import { Vec4Heap } from '../../src/gpu-layout/vec4-heap.ts';
import { buildTextureAtlas } from '../../src/materials/textures/texture-atlas.ts';
import { readTextureInfo, sampleTextureInfo, textureLod, type Rgba } from '../../src/materials/textures/reference-sampler.ts';
import { applyTextureTransform, textureTransformMatrix } from '../../src/scene/texture-transform.ts';
import type { WavefrontMagFilter, WavefrontWrapMode } from '../../src/scene/types.ts';
import { srgbToLinear } from '../../src/film/tone-mapping.ts';
import { orthographicCameraNode, quad, renderScene, roundTrip } from './gltf-scenes.ts';

/** 4 x 4 texels of distinct colours (a colour checker): a wrong texel shows as a large error. */
const TEXELS = Uint8Array.from({ length: 64 }, (_, i) => (i % 4 === 3 ? 255 : (53 * i + 29) % 256));
const checkerPng = (): Uint8Array => encodePng({ width: 4, height: 4, data: TEXELS, channels: 4 });

const PLANES = 4;
const WIDTH = 16 * PLANES;
const HEIGHT = 16;

/** Pixel centre -> plane index and its uv0 (each plane spans 16 x 16 pixels, uv (0, 0) top left). */
function pixelUv(x: number, y: number): { plane: number; u: number; v: number } {
  return { plane: Math.floor(x / 16), u: ((x % 16) + 0.5) / 16, v: (y + 0.5) / 16 };
}

interface PlaneCase {
  name: string;
  wrapS: GLTF.TextureWrapMode;
  wrapT: GLTF.TextureWrapMode;
  offset: [number, number];
  rotation: number;
  scale: [number, number];
  /** TEXCOORD set named by the texture info, and the KHR_texture_transform override (if any). */
  infoTexCoord: number;
  transformTexCoord?: number;
  factor?: [number, number, number, number];
  /** COLOR_0 red channel from `colorRed[0]` at u = 0 to `colorRed[1]` at u = 1. */
  colorRed?: [number, number];
}

const { REPEAT, CLAMP_TO_EDGE, MIRRORED_REPEAT } = TextureInfo.WrapMode;
// Offset (-0.5, -0.25) and scale 2 put texel edges at pixels 2k + 4 (u) and 2k + 2 (v); the rotated
// case (pi/2, offset (0.25, 1.5)) at 12 - 2k and 2k - 2. Every case reads uv outside [0, 1].
const CASES: PlaneCase[] = [
  { name: 'repeat', wrapS: REPEAT, wrapT: REPEAT, offset: [-0.5, -0.25], rotation: 0, scale: [2, 2], infoTexCoord: 0 },
  { name: 'clamp-to-edge', wrapS: CLAMP_TO_EDGE, wrapT: CLAMP_TO_EDGE, offset: [-0.5, -0.25], rotation: 0, scale: [2, 2], infoTexCoord: 0, factor: [0.5, 1, 0.75, 1] },
  { name: 'mirrored-repeat + COLOR_0', wrapS: MIRRORED_REPEAT, wrapT: MIRRORED_REPEAT, offset: [-0.5, -0.25], rotation: 0, scale: [2, 2], infoTexCoord: 0, colorRed: [0.2, 1] },
  { name: 'rotated, uv1 by transform override, repeat x mirrored', wrapS: REPEAT, wrapT: MIRRORED_REPEAT, offset: [0.25, 1.5], rotation: Math.PI / 2, scale: [2, 2], infoTexCoord: 0, transformTexCoord: 1 },
];

function planesDocument(filter: GLTF.TextureMagFilter): Document {
  const doc = new Document();
  const transforms = doc.createExtension(KHRTextureTransform);
  const ior = doc.createExtension(KHRMaterialsIOR);
  const buffer = doc.createBuffer();
  const image = doc.createTexture('colour checker').setMimeType('image/png').setImage(checkerPng());
  const scene = doc.createScene().addChild(orthographicCameraNode(doc, 2));
  CASES.forEach((c, k) => {
    const material = doc.createMaterial(c.name).setMetallicFactor(0).setRoughnessFactor(1).setBaseColorTexture(image).setExtension('KHR_materials_ior', ior.createIOR().setIOR(1));
    if (c.factor) material.setBaseColorFactor(c.factor);
    const transform = transforms.createTransform().setOffset(c.offset).setRotation(c.rotation).setScale(c.scale);
    if (c.transformTexCoord !== undefined) transform.setTexCoord(c.transformTexCoord);
    material.getBaseColorTextureInfo()!.setWrapS(c.wrapS).setWrapT(c.wrapT).setMagFilter(filter).setTexCoord(c.infoTexCoord).setExtension('KHR_texture_transform', transform);
    const x0 = -4 + 2 * k;
    const colors = c.colorRed ? [c.colorRed[0], 1, 1, 1, c.colorRed[1], 1, 1, 1, c.colorRed[1], 1, 1, 1, c.colorRed[0], 1, 1, 1] : undefined;
    scene.addChild(doc.createNode(c.name).setMesh(quad(doc, buffer, material, { x0, y0: -1, x1: x0 + 2, y1: 1, normals: true, uv1: true, ...(colors ? { colors } : {}) })));
  });
  return doc;
}

const WRAP_NAMES: Readonly<Record<number, WavefrontWrapMode>> = { [REPEAT]: 'repeat', [CLAMP_TO_EDGE]: 'clamp-to-edge', [MIRRORED_REPEAT]: 'mirrored-repeat' };

/**
 * The CPU reference of each plane's albedo at a pixel centre. It is built from the test's own
 * description of the planes (CASES), not from what the loader returned, so a loader that mapped a
 * wrap mode, transform or uv set wrongly would fail here too; the atlas is packed as the renderer
 * packs it, and sampled by the reference sampler.
 */
function referenceAlbedo(magFilter: WavefrontMagFilter): (x: number, y: number) => Rgba {
  const heap = new Vec4Heap();
  const image = { width: 4, height: 4, data: TEXELS };
  const textures = CASES.map((c) => ({ image, sampler: { wrapS: WRAP_NAMES[c.wrapS]!, wrapT: WRAP_NAMES[c.wrapT]!, magFilter } }));
  const atlas = buildTextureAtlas({ textures }, CASES.map((_, i) => ({ texture: i, srgb: true })), heap, { maxTextureDimension2D: 8192, maxTextureArrayLayers: 256 });
  const data = heap.finish();
  return (x, y) => {
    const { plane, u, v } = pixelUv(x, y);
    const c = CASES[plane]!;
    const info = readTextureInfo(data, atlas.infoOffset(plane, true));
    const rows = textureTransformMatrix({ offset: c.offset, rotation: c.rotation, scale: c.scale });
    // KHR_texture_transform's texCoord, where given, replaces the texture info's.
    const texCoord = c.transformTexCoord ?? c.infoTexCoord;
    const [su, sv] = applyTextureTransform(rows, texCoord === 1 ? 1 - u : u, v);
    // The camera's ray cone: one pixel (1/8 unit) wide, hitting the plane head on; each triangle
    // has world area 2 and uv area 1/2.
    const lod = textureLod({ ...rows, texture: 0, texCoord, scale: 1, flags: 0 }, info, { widthOverCos: 1 / 8, worldArea: 2, uvArea: [0.5, 0.5] });
    const t = sampleTextureInfo(atlas, info, [su, sv], lod, true);
    const factor = c.factor ?? [1, 1, 1, 1];
    const red = c.colorRed ? c.colorRed[0] + (c.colorRed[1] - c.colorRed[0]) * u : 1;
    return [t[0] * factor[0] * red, t[1] * factor[1], t[2] * factor[2], t[3] * factor[3]];
  };
}

for (const [filterName, filter, tolerance] of [['nearest', TextureInfo.MagFilter.NEAREST, 1e-4], ['linear', TextureInfo.MagFilter.LINEAR, 2e-3]] as const) {
  test(`checker planes (${filterName} filter): every wrap mode and KHR_texture_transform match the CPU reference sampler`, async () => {
    const scene = await roundTrip(planesDocument(filter));
    assert.equal(scene.camera.type, 'orthographic');
    assert.equal(scene.images.length, 1, 'one image for the four planes');
    const result = await renderScene(scene, { width: WIDTH, height: HEIGHT, aovs: true, environment: { color: [1, 1, 1] } }, 64);
    assert.equal(result.stats.invalidSamples, 0);
    const albedo = result.albedo!;
    const reference = referenceAlbedo(filterName);
    const worst = CASES.map(() => 0);
    for (let y = 0; y < HEIGHT; y++) {
      for (let x = 0; x < WIDTH; x++) {
        const want = reference(x, y);
        const { plane } = pixelUv(x, y);
        // COLOR_0's gradient adds its own (linear) variation within each pixel to the quadrature.
        const allowed = CASES[plane]!.colorRed ? 2.5 * tolerance : tolerance;
        for (let c = 0; c < 3; c++) {
          const got = albedo[4 * (y * WIDTH + x) + c]!;
          const error = Math.abs(got - want[c]!);
          worst[plane] = Math.max(worst[plane]!, error);
          assert.ok(error <= allowed, `${CASES[plane]!.name}: pixel (${x % 16}, ${y}) channel ${c}: GPU ${got}, reference ${want[c]}`);
        }
      }
    }
    // The planes show different texels: the comparison is not trivially satisfied.
    const distinct = new Set(Array.from({ length: WIDTH }, (_, x) => albedo[4 * (5 * WIDTH + x)]!.toFixed(3)));
    assert.ok(distinct.size >= 8, `row 5 shows ${distinct.size} distinct values`);
  });
}

/** A 2 x 2 PNG of `rgba` texels (top row first). */
function png2x2(rgba: readonly number[]): Uint8Array {
  return encodePng({ width: 2, height: 2, data: Uint8Array.from(rgba), channels: 4 });
}

function nearest(texture: TextureInfo | null): void {
  texture!.setMagFilter(TextureInfo.MagFilter.NEAREST).setMinFilter(TextureInfo.MinFilter.NEAREST);
}

test('emissive texture (uv1 with a transform) is read at level 0: radiance equals emissiveFactor x strength x texel', async () => {
  const texels = [250, 30, 10, 255, 20, 220, 90, 255, 128, 128, 255, 255, 255, 255, 255, 255];
  const doc = new Document();
  const buffer = doc.createBuffer();
  const emissive = doc.createTexture('glow').setMimeType('image/png').setImage(png2x2(texels));
  const strength = doc.createExtension(KHRMaterialsEmissiveStrength).createEmissiveStrength().setEmissiveStrength(3);
  const transform = doc.createExtension(KHRTextureTransform).createTransform().setOffset([0.5, 0]);
  const material = doc.createMaterial('lamp').setBaseColorFactor([0, 0, 0, 1]).setEmissiveFactor([1, 0.5, 0.25]).setEmissiveTexture(emissive)
    .setExtension('KHR_materials_emissive_strength', strength).setExtension('KHR_materials_ior', doc.createExtension(KHRMaterialsIOR).createIOR().setIOR(1));
  nearest(material.getEmissiveTextureInfo());
  material.getEmissiveTextureInfo()!.setTexCoord(1).setExtension('KHR_texture_transform', transform);
  doc.createScene().addChild(orthographicCameraNode(doc, 2)).addChild(doc.createNode('lamp').setMesh(quad(doc, buffer, material, { x0: -1, y0: -1, x1: 1, y1: 1, uv1: true })));
  const scene = await roundTrip(doc);
  const { radiance } = await renderScene(scene, { width: 16, height: 16, environment: { color: [0, 0, 0] } }, 4);
  for (let y = 0; y < 16; y++) {
    for (let x = 0; x < 16; x++) {
      // uv1 = (1 - u, v), shifted by half a texture in u: texel column floor(2 * frac(1 - u + 0.5)).
      const u = 1 - (x + 0.5) / 16 + 0.5;
      const column = Math.floor(2 * (u - Math.floor(u)));
      const row = y < 8 ? 0 : 1;
      const texel = texels.slice(4 * (2 * row + column), 4 * (2 * row + column) + 3).map((b) => srgbToLinear(b / 255));
      [1, 0.5, 0.25].forEach((f, c) => {
        const want = 3 * f * texel[c]!;
        const got = radiance[4 * (y * 16 + x) + c]!;
        assert.ok(Math.abs(got - want) <= 1e-5 * Math.max(1, want), `pixel (${x}, ${y}) channel ${c}: ${got} vs ${want}`);
      });
    }
  }
});

test('normal texture with scale, MikkTSpace tangents from the loader: the shading normal AOV', async () => {
  // m = (204, 128, 230) / 255 * 2 - 1; the quad has NORMAL but no TANGENT.
  const texel = [204, 128, 230, 255];
  const doc = new Document();
  const buffer = doc.createBuffer();
  const map = doc.createTexture('bumps').setMimeType('image/png').setImage(png2x2([...texel, ...texel, ...texel, ...texel]));
  const material = doc.createMaterial('bumpy').setMetallicFactor(0).setNormalTexture(map).setNormalScale(0.5);
  doc.createScene().addChild(orthographicCameraNode(doc, 2)).addChild(doc.createNode('plane').setMesh(quad(doc, buffer, material, { x0: -1, y0: -1, x1: 1, y1: 1, normals: true })));
  const scene = await roundTrip(doc);
  assert.ok(scene.meshes[0]!.tangents !== undefined, 'tangents generated');
  const { normal } = await renderScene(scene, { width: 8, height: 8, aovs: true, environment: { color: [1, 1, 1] } }, 2);
  // glTF 2.0 section 3.9.3: n = normalize(T (m.x s) + B (m.y s) + N m.z), T = dP/du = +x and
  // B = -dP/dv = +y (v grows downwards; a normal map's +Y is up), so n = normalize(m.x s, m.y s, m.z).
  const m = texel.slice(0, 3).map((b) => (b / 255) * 2 - 1);
  const n = [0.5 * m[0]!, 0.5 * m[1]!, m[2]!];
  const len = Math.hypot(...n);
  for (let i = 0; i < 64; i++) {
    for (let c = 0; c < 3; c++) assert.ok(Math.abs(normal![4 * i + c]! - n[c]! / len) < 1e-3, `pixel ${i} channel ${c}: ${normal![4 * i + c]} vs ${n[c]! / len}`);
  }
});

/**
 * A floor seen at 45 degrees by an orthographic camera; the mirror direction of every view ray
 * meets a large double-sided emitter of radiance 1. Its metallic-roughness texture (nearest, three
 * texel columns, one per third of the view) makes the left third a smooth white conductor (G = 0,
 * B = 255: a perfect mirror, F = 1), the middle a rough one (G = 255) and the right a Lambertian
 * dielectric (B = 0, ior 1). Only the mirror reflects the emitter's radiance exactly; the others
 * spread it over the hemisphere, most of which sees black.
 */
function mirrorScene(extra?: (doc: Document, floor: Material) => void): Document {
  const doc = new Document();
  const buffer = doc.createBuffer();
  const ior = doc.createExtension(KHRMaterialsIOR);
  const mr = doc.createTexture('orm').setMimeType('image/png').setImage(encodePng({ width: 3, height: 1, channels: 4, data: Uint8Array.from([255, 0, 255, 255, 90, 255, 255, 255, 30, 0, 0, 255]) }));
  const floor = doc.createMaterial('floor').setBaseColorFactor([1, 1, 1, 1]).setMetallicFactor(1).setRoughnessFactor(1).setMetallicRoughnessTexture(mr).setExtension('KHR_materials_ior', ior.createIOR().setIOR(1));
  nearest(floor.getMetallicRoughnessTextureInfo());
  extra?.(doc, floor);
  const lamp = doc.createMaterial('lamp').setBaseColorFactor([0, 0, 0, 1]).setEmissiveFactor([1, 1, 1]).setDoubleSided(true).setExtension('KHR_materials_ior', ior.createIOR().setIOR(1));
  const s = Math.SQRT1_2;
  // The camera at (0, 3, 3) looks along (0, -1, -1) / sqrt(2) (rotated -45 degrees about x).
  const camera = doc.createCamera('view').setType('orthographic').setYMag(1).setXMag(3).setZNear(0.01).setZFar(100);
  const eye = doc.createNode('eye').setCamera(camera).setTranslation([0, 3, 3]).setRotation([-Math.sin(Math.PI / 8), 0, 0, Math.cos(Math.PI / 8)]);
  // The floor is y = 0; view rays reflect into (0, 1, -1) / sqrt(2). The emitter: a 12 x 12
  // square in the plane y - z = 6 around (0, 3, -3), across those reflected rays, never crossed by
  // the view rays (along which y - z stays 0).
  const c = [0, 3, -3];
  const a = [6, 0, 0];
  const b = [0, 6 * s, 6 * s];
  const corner = (i: number, j: number): number[] => c.map((v, k) => v + i * a[k]! + j * b[k]!);
  const emitterPositions = [...corner(-1, -1), ...corner(1, -1), ...corner(1, 1), ...corner(-1, 1)];
  const emitter = doc.createMesh('emitter').addPrimitive(
    doc.createPrimitive()
      .setAttribute('POSITION', doc.createAccessor().setType('VEC3').setArray(new Float32Array(emitterPositions)).setBuffer(buffer))
      .setIndices(doc.createAccessor().setType('SCALAR').setArray(new Uint16Array([0, 1, 2, 0, 2, 3])).setBuffer(buffer))
      .setMaterial(lamp),
  );
  // The floor: the quad helper's z = 0 plane turned to y = 0 (rotation -90 degrees about x), u along x.
  const floorNode = doc.createNode('floor').setMesh(quad(doc, buffer, floor, { x0: -3, y0: -3, x1: 3, y1: 3, normals: true })).setRotation([-s, 0, 0, s]);
  doc.createScene().addChild(eye).addChild(floorNode).addChild(doc.createNode('emitter').setMesh(emitter));
  return doc;
}

test('metallic-roughness texture: B is metallic and G roughness (a mirror third shows the emitter exactly); occlusion is loaded but not applied', async () => {
  const scene = await roundTrip(mirrorScene());
  assert.equal(scene.camera.type, 'orthographic');
  const width = 48;
  const height = 16;
  const options = { width, height, environment: { color: [0, 0, 0] }, maxDepth: 3 };
  const { radiance, stats } = await renderScene(scene, options, 16);
  assert.equal(stats.invalidSamples, 0);
  const third = (k: number): number => {
    let sum = 0;
    for (let y = 0; y < height; y++) for (let x = 16 * k + 1; x < 16 * k + 15; x++) sum += radiance[4 * (y * width + x) + 1]! / (height * 14);
    return sum;
  };
  const [mirror, rough, lambert] = [third(0), third(1), third(2)];
  assert.ok(Math.abs(mirror - 1) < 0.01, `mirror third: ${mirror}`);
  assert.ok(rough > 0.05 && rough < 0.85, `rough conductor third: ${rough}`);
  assert.ok(lambert > 0.05 && lambert < 0.85, `Lambertian third: ${lambert}`);

  // The same scene with an occlusion texture of zeros renders the same image, sample for sample.
  const black = png2x2(Array.from({ length: 16 }, (_, i) => (i % 4 === 3 ? 255 : 0)));
  const occluded = mirrorScene((doc, floor) => floor.setOcclusionTexture(doc.createTexture('ao').setMimeType('image/png').setImage(black)).setOcclusionStrength(1));
  const withOcclusion = await roundTrip(occluded);
  assert.ok(withOcclusion.materials.some((m) => m.occlusionTexture !== undefined), 'the occlusion texture is loaded');
  const again = await renderScene(withOcclusion, options, 16);
  assert.deepEqual(Array.from(again.radiance), Array.from(radiance));
});
