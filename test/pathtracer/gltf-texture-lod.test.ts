// Minified textures must not alias: mip levels are chosen by ray cones (Akenine-Moller et al.,
// "Improved Shader and Texture Level of Detail Using Ray Cones", JCGT 10(1), 2021), so a checker
// of one-texel squares seen from afar shows its mean in every sample, while the same texture read
// from level 0 only (minFilter NEAREST: GL semantics, no mipmaps) gives every sample a black or
// white texel: noise at low sample counts, which only converges to that mean as samples
// accumulate. The checker is black and white in sRGB, 0 and 1 in linear light; its mean is 0.5,
// and every mip level from 1 on holds exactly that mean, rounded to the nearest sRGB byte (188).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { Document, TextureInfo } from '@gltf-transform/core';
import { KHRMaterialsIOR, KHRTextureTransform } from '@gltf-transform/extensions';
import { encode as encodePng } from 'fast-png';
import { linearToSrgb, srgbToLinear } from '../../src/film/tone-mapping.ts';
import { orthographicCameraNode, quad, renderScene, roundTrip } from './gltf-scenes.ts';

const CHECKER = 64;
/** Level >= 1 of the checker: the mean 0.5, stored as an sRGB byte and decoded again. */
const MIP_MEAN = srgbToLinear(Math.round(255 * linearToSrgb(0.5)) / 255);

function checkerPng(): Uint8Array {
  const data = new Uint8Array(CHECKER * CHECKER * 4);
  for (let y = 0; y < CHECKER; y++) {
    for (let x = 0; x < CHECKER; x++) data.set((x + y) % 2 === 0 ? [255, 255, 255, 255] : [0, 0, 0, 255], 4 * (y * CHECKER + x));
  }
  return encodePng({ width: CHECKER, height: CHECKER, data, channels: 4 });
}

/** A Lambertian checker material: mipmapped (glTF's default sampler) or level 0 only. */
function checkerMaterial(doc: Document, mipmapped: boolean, repeats?: [number, number]) {
  const texture = doc.createTexture('checker').setMimeType('image/png').setImage(checkerPng());
  const material = doc.createMaterial('checker').setMetallicFactor(0).setBaseColorTexture(texture)
    .setExtension('KHR_materials_ior', doc.createExtension(KHRMaterialsIOR).createIOR().setIOR(1));
  const info = material.getBaseColorTextureInfo()!;
  if (!mipmapped) info.setMinFilter(TextureInfo.MinFilter.NEAREST);
  if (repeats) info.setExtension('KHR_texture_transform', doc.createExtension(KHRTextureTransform).createTransform().setScale(repeats));
  return material;
}

function stats(values: number[]): { mean: number; std: number; min: number; max: number } {
  const mean = values.reduce((a, b) => a + b, 0) / values.length;
  const std = Math.sqrt(values.reduce((a, b) => a + (b - mean) ** 2, 0) / values.length);
  return { mean, std, min: Math.min(...values), max: Math.max(...values) };
}

test('orthographic view, 4 x 4 texels per pixel: mipmaps give the mean in one sample; level 0 alone aliases into noise', async () => {
  const albedo = async (mipmapped: boolean, spp: number): Promise<number[]> => {
    const doc = new Document();
    const plane = quad(doc, doc.createBuffer(), checkerMaterial(doc, mipmapped), { x0: -1, y0: -1, x1: 1, y1: 1, normals: true });
    doc.createScene().addChild(orthographicCameraNode(doc, 2)).addChild(doc.createNode('plane').setMesh(plane));
    const result = await renderScene(await roundTrip(doc), { width: 16, height: 16, aovs: true, environment: { color: [1, 1, 1] }, maxDepth: 1 }, spp);
    return Array.from({ length: 256 }, (_, i) => result.albedo![4 * i]!);
  };
  // The ray cone is one pixel (2/16) wide and a texel 2/64: lambda = log2(4) = 2.
  const filtered = stats(await albedo(true, 1));
  assert.ok(filtered.max - filtered.min < 1e-5 && Math.abs(filtered.mean - MIP_MEAN) < 1e-5, `mipmapped, 1 spp: ${JSON.stringify(filtered)}`);
  assert.ok(Math.abs(MIP_MEAN - 0.5) < 0.005, 'the mip levels hold the mean');
  const aliased = stats(await albedo(false, 1));
  assert.ok(aliased.std > 0.4, `level 0 only, 1 spp: every sample is one black or white texel: ${JSON.stringify(aliased)}`);
  // With many samples per pixel the unfiltered image converges to the same mean: each pixel averages
  // 256 samples of a 0/1 variable (standard error 1/32), the image 65536 (1/512).
  const converged = stats(await albedo(false, 256));
  assert.ok(Math.abs(converged.mean - 0.5) < 0.01, `level 0 only, 256 spp, image mean: ${JSON.stringify(converged)}`);
  assert.ok(converged.max - 0.5 < 0.16 && 0.5 - converged.min < 0.16, `level 0 only, 256 spp, pixels within 5 standard errors: ${JSON.stringify(converged)}`);
});

test('perspective view of a receding checker floor: distant rows show the mean, near rows keep the checker', async () => {
  const WIDTH = 32;
  const HEIGHT = 32;
  const rows = async (mipmapped: boolean): Promise<{ far: number[]; near: number[] }> => {
    const doc = new Document();
    // The floor y = 0, x in [-100, 100], z in [-200, 5]; one checker texel is 0.2 units.
    const floor = quad(doc, doc.createBuffer(), checkerMaterial(doc, mipmapped, [200 / 12.8, 205 / 12.8]), { x0: -100, y0: -5, x1: 100, y1: 200, normals: true });
    const camera = doc.createCamera('eye').setType('perspective').setYFov((40 * Math.PI) / 180).setZNear(0.01);
    const pitch = (-15 * Math.PI) / 180;
    doc.createScene()
      .addChild(doc.createNode('eye').setCamera(camera).setTranslation([0, 0.5, 0]).setRotation([Math.sin(pitch / 2), 0, 0, Math.cos(pitch / 2)]))
      .addChild(doc.createNode('floor').setMesh(floor).setRotation([-Math.SQRT1_2, 0, 0, Math.SQRT1_2]));
    const result = await renderScene(await roundTrip(doc), { width: WIDTH, height: HEIGHT, aovs: true, environment: { color: [1, 1, 1] }, maxDepth: 1 }, 1);
    const pick = (from: number, to: number): number[] => {
      const out: number[] = [];
      for (let y = from; y <= to; y++) for (let x = 0; x < WIDTH; x++) out.push(result.albedo![4 * (y * WIDTH + x)]!);
      return out;
    };
    // The horizon is near row 4 (15 degrees above the centre of a 40 degree view). Rows 5..9 meet
    // the floor 5 to 18 units away at 2 to 5 degrees: a pixel's cone spans 1 to 6 units of floor
    // over |cos|, 5 to 30 texels, lambda > 2. Rows 26..31 are about 1 unit away: a pixel covers
    // 0.03 units, a sixth of a texel, magnified.
    return { far: pick(5, 9), near: pick(26, 31) };
  };
  const mip = await rows(true);
  const far = stats(mip.far);
  assert.ok(Math.abs(far.mean - MIP_MEAN) < 0.01 && far.max - far.min < 0.02, `mipmapped, distant rows: ${JSON.stringify(far)}`);
  const near = stats(mip.near);
  // Magnified and bilinearly filtered, the near checker still reaches close to black and white.
  assert.ok(near.min < 0.25 && near.max > 0.75, `mipmapped, near rows keep the checker: ${JSON.stringify(near)}`);
  const aliased = stats((await rows(false)).far);
  assert.ok(aliased.std > 0.4, `level 0 only, distant rows alias: ${JSON.stringify(aliased)}`);
});
