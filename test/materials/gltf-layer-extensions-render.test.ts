// The newer KHR material extensions through the whole glTF path (built with @gltf-transform/core,
// written as GLB, read by loadGltfScene, rendered on the GPU): a KHR extension texture
// (transmissionTexture, a two-texel checker) must render each half as the plain factor it encodes,
// and iridescence, anisotropy and diffuse-transmission swatches must render finite, non-black, with
// no invalid samples, and differ from the same materials with the extension left out by more than
// the renderer's own noise (the same scene rendered with another seed).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { Document, TextureInfo, type Material } from '@gltf-transform/core';
import { KHRMaterialsAnisotropy, KHRMaterialsDiffuseTransmission, KHRMaterialsEmissiveStrength, KHRMaterialsIOR, KHRMaterialsIridescence, KHRMaterialsTransmission } from '@gltf-transform/extensions';
import { encode as encodePng } from 'fast-png';
import type { WavefrontMaterialInput } from '../../src/scene/types.ts';
import { orthographicCameraNode, quad, renderScene, roundTrip } from '../pathtracer/gltf-scenes.ts';

function materialOf(scene: { meshes?: readonly { material?: unknown }[]; materials?: readonly WavefrontMaterialInput[] }, name: string): WavefrontMaterialInput {
  const all = [...(scene.materials ?? []), ...(scene.meshes ?? []).map((m) => m.material).filter((m): m is WavefrontMaterialInput => typeof m === 'object' && m !== null)];
  const found = all.find((m) => m.name === name);
  assert.ok(found, `material ${name} in the loaded scene`);
  return found;
}

const E = [2, 3, 4];

/** A black emitter quad behind everything at z = -1, facing the camera (emissive_strength for HDR). */
function addBackEmitter(doc: Document, buffer: ReturnType<Document['createBuffer']>, halfWidth: number): void {
  const light = doc.createMaterial('emitter').setBaseColorFactor([0, 0, 0, 1]).setMetallicFactor(0).setRoughnessFactor(1).setEmissiveFactor([E[0]! / 4, E[1]! / 4, E[2]! / 4])
    .setExtension('KHR_materials_emissive_strength', doc.createExtension(KHRMaterialsEmissiveStrength).createEmissiveStrength().setEmissiveStrength(4))
    .setExtension('KHR_materials_ior', doc.createExtension(KHRMaterialsIOR).createIOR().setIOR(1));
  doc.getRoot().listScenes()[0]!.addChild(doc.createNode('emitter').setMesh(quad(doc, buffer, light, { x0: -halfWidth - 1, y0: -2, x1: halfWidth + 1, y1: 2, z: -1 })));
}

/** Mean of channel c over pixel columns [x0, x1) and rows [y0, y1) of a width-wide RGBA image. */
function regionMean(image: Float32Array, width: number, c: number, x0: number, x1: number, y0: number, y1: number): number {
  let sum = 0;
  for (let y = y0; y < y1; y++) for (let x = x0; x < x1; x++) sum += image[4 * (y * width + x) + c]!;
  return sum / ((x1 - x0) * (y1 - y0));
}

// Texels of the transmission checker (red channel; non-colour data is linear: 128 / 255).
const TEXEL_HIGH = 255;
const TEXEL_LOW = 128;
const TRANSMISSION = 0.8;

test('glTF transmissionTexture (two-texel checker): each half renders as the plain factor it encodes', async (t) => {
  const SIZE = 16;
  // factor: a plain transmissionFactor; 'texture': TRANSMISSION times the checker.
  const build = (factor: number | 'texture'): Document => {
    const doc = new Document();
    const buffer = doc.createBuffer();
    const transmission = doc.createExtension(KHRMaterialsTransmission).createTransmission().setTransmissionFactor(factor === 'texture' ? TRANSMISSION : factor);
    const glass = doc.createMaterial('glass').setBaseColorFactor([1, 1, 1, 1]).setMetallicFactor(0).setRoughnessFactor(0)
      .setExtension('KHR_materials_transmission', transmission)
      .setExtension('KHR_materials_ior', doc.createExtension(KHRMaterialsIOR).createIOR().setIOR(1.5));
    if (factor === 'texture') {
      const png = encodePng({ width: 2, height: 1, channels: 4, data: Uint8Array.from([TEXEL_HIGH, 0, 0, 255, TEXEL_LOW, 0, 0, 255]) });
      transmission.setTransmissionTexture(doc.createTexture('checker').setMimeType('image/png').setImage(png));
      transmission.getTransmissionTextureInfo()!.setMagFilter(TextureInfo.MagFilter.NEAREST).setMinFilter(TextureInfo.MinFilter.NEAREST);
    }
    doc.createScene().addChild(doc.createNode('glass').setMesh(quad(doc, buffer, glass, { x0: -1, y0: -1, x1: 1, y1: 1 })))
      .addChild(orthographicCameraNode(doc, 2, [0, 0, 3]));
    addBackEmitter(doc, buffer, 1);
    return doc;
  };
  const options = { width: SIZE, height: SIZE, maxDepth: 8 };
  const textured = await roundTrip(build('texture'));
  assert.equal(materialOf(textured, 'glass').transmissionFactor, TRANSMISSION);
  assert.ok(materialOf(textured, 'glass').transmissionTexture, 'the transmissionTexture reference loads');
  const images = await Promise.all([textured, await roundTrip(build(TRANSMISSION * TEXEL_HIGH / 255)), await roundTrip(build(TRANSMISSION * TEXEL_LOW / 255))]
    .map(async (scene) => {
      const r = await renderScene(scene, options, 64);
      assert.equal(r.stats.invalidSamples, 0);
      return r.radiance;
    }));
  const [tex, high, low] = images as [Float32Array, Float32Array, Float32Array];
  // uv (0, 0) is the quad's top left: texel 0 covers the left half (columns 0-7), texel 1 the right;
  // the columns at the texel edge (7, 8) are left out.
  for (let c = 0; c < 3; c++) {
    const left = regionMean(tex, SIZE, c, 1, 7, 1, SIZE - 1);
    const right = regionMean(tex, SIZE, c, 9, SIZE - 1, 1, SIZE - 1);
    const leftPlain = regionMean(high, SIZE, c, 1, 7, 1, SIZE - 1);
    const rightPlain = regionMean(low, SIZE, c, 9, SIZE - 1, 1, SIZE - 1);
    t.diagnostic(`channel ${c}: textured left ${left.toFixed(4)} vs plain ${leftPlain.toFixed(4)}; right ${right.toFixed(4)} vs plain ${rightPlain.toFixed(4)}`);
    // Same seed and pixels: the halves follow the plain renders' sample paths; 2% covers the
    // texture's 8-bit storage of the factor (1/255 = 0.4% relative on the low texel).
    assert.ok(Math.abs(left - leftPlain) <= 0.02 * leftPlain, `left half channel ${c}: ${left} vs ${leftPlain}`);
    assert.ok(Math.abs(right - rightPlain) <= 0.02 * rightPlain, `right half channel ${c}: ${right} vs ${rightPlain}`);
    // The two halves are told apart: the low texel transmits markedly less.
    assert.ok(right < 0.8 * left, `channel ${c}: right ${right} vs left ${left}`);
  }
});

test('glTF iridescence, anisotropy and diffuse-transmission swatches render valid, non-black, and differ from the extension left out', async (t) => {
  const WIDTH = 48;
  const HEIGHT = 16;
  const names = ['iridescent', 'brushed', 'leaf'] as const;
  const build = (extensions: boolean): Document => {
    const doc = new Document();
    const buffer = doc.createBuffer();
    const iridescent = doc.createMaterial('iridescent').setBaseColorFactor([0.6, 0.6, 0.6, 1]).setMetallicFactor(1).setRoughnessFactor(0.3);
    const brushed = doc.createMaterial('brushed').setBaseColorFactor([0.9, 0.9, 0.9, 1]).setMetallicFactor(1).setRoughnessFactor(0.35);
    const leaf = doc.createMaterial('leaf').setBaseColorFactor([0.8, 0.8, 0.8, 1]).setMetallicFactor(0).setRoughnessFactor(1);
    if (extensions) {
      iridescent.setExtension('KHR_materials_iridescence', doc.createExtension(KHRMaterialsIridescence).createIridescence()
        .setIridescenceFactor(1).setIridescenceIOR(1.3).setIridescenceThicknessMinimum(100).setIridescenceThicknessMaximum(400));
      brushed.setExtension('KHR_materials_anisotropy', doc.createExtension(KHRMaterialsAnisotropy).createAnisotropy().setAnisotropyStrength(0.9).setAnisotropyRotation(Math.PI / 2));
      leaf.setExtension('KHR_materials_diffuse_transmission', doc.createExtension(KHRMaterialsDiffuseTransmission).createDiffuseTransmission()
        .setDiffuseTransmissionFactor(1).setDiffuseTransmissionColorFactor([1, 0.5, 0.25]));
    }
    // (A white metal would not do for iridescence: a lossless film over a perfect mirror still
    // reflects everything, so the image would not change.)
    const scene = doc.createScene();
    // Swatch k spans x in [-3 + 2k + 0.05, -1 + 2k - 0.05]: pixel columns 16k + 1 .. 16k + 14.
    [iridescent, brushed, leaf].forEach((m: Material, k) => {
      scene.addChild(doc.createNode(names[k]!).setMesh(quad(doc, buffer, m, { x0: -3 + 2 * k + 0.05, y0: -1, x1: -1 + 2 * k - 0.05, y1: 1 })));
    });
    scene.addChild(orthographicCameraNode(doc, 2, [0, 0, 3]));
    addBackEmitter(doc, buffer, 3);
    return doc;
  };
  const on = await roundTrip(build(true));
  const i = materialOf(on, 'iridescent');
  assert.equal(i.iridescenceFactor, 1);
  assert.ok(Math.abs(i.iridescenceIor! - 1.3) < 1e-6 && i.iridescenceThicknessMaximum === 400);
  const b = materialOf(on, 'brushed');
  assert.ok(Math.abs(b.anisotropyStrength! - 0.9) < 1e-6 && Math.abs(b.anisotropyRotation! - Math.PI / 2) < 1e-6);
  const l = materialOf(on, 'leaf');
  assert.equal(l.diffuseTransmissionFactor, 1);
  assert.deepEqual(l.diffuseTransmissionColorFactor, [1, 0.5, 0.25]);
  const off = await roundTrip(build(false));
  // A rectangle light above and in front (facing the swatches at 45 degrees) for the specular lobes,
  // a dim environment, and the emitter behind for diffuse transmission.
  const lights = [{ type: 'rectangle' as const, center: [0, 2, 2], edgeU: [6, 0, 0], edgeV: [0, -0.5, 0.5], emission: [1, 1, 1], intensity: 3 }];
  const options = { width: WIDTH, height: HEIGHT, maxDepth: 6, lights, environment: { color: [0.2, 0.2, 0.2] } };
  const render = async (scene: typeof on, seed: number): Promise<Float32Array> => {
    const r = await renderScene(scene, { ...options, seed }, 64);
    assert.equal(r.stats.invalidSamples, 0);
    return r.radiance;
  };
  const withExt = await render(on, 5);
  const without = await render(off, 5);
  const withoutOtherSeed = await render(off, 6);
  /** Mean absolute per-pixel difference over swatch k (all channels). */
  const meanAbsDiff = (a: Float32Array, b2: Float32Array, k: number): number => {
    let s = 0;
    let n = 0;
    for (let y = 1; y < HEIGHT - 1; y++) for (let x = 16 * k + 2; x < 16 * k + 14; x++) for (let c = 0; c < 3; c++) { s += Math.abs(a[4 * (y * WIDTH + x) + c]! - b2[4 * (y * WIDTH + x) + c]!); n++; }
    return s / n;
  };
  names.forEach((name, k) => {
    const means = [0, 1, 2].map((c) => regionMean(withExt, WIDTH, c, 16 * k + 2, 16 * k + 14, 1, HEIGHT - 1));
    const meansOff = [0, 1, 2].map((c) => regionMean(without, WIDTH, c, 16 * k + 2, 16 * k + 14, 1, HEIGHT - 1));
    const change = meanAbsDiff(withExt, without, k);
    const noise = meanAbsDiff(without, withoutOtherSeed, k);
    t.diagnostic(`${name}: rgb ${means.map((v) => v.toFixed(4)).join(' ')} (off ${meansOff.map((v) => v.toFixed(4)).join(' ')}); mean |on - off| ${change.toFixed(4)}, noise ${noise.toFixed(4)}`);
    assert.ok(means.every(Number.isFinite), `${name}: finite`);
    assert.ok(Math.max(...means) > 0.01, `${name}: not black`);
    assert.ok(change > 3 * noise, `${name}: the extension changes the image (${change}) beyond noise (${noise})`);
  });
});
