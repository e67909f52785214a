// KHR_materials_transmission / _ior / _volume end to end (renderer, real WGSL): closed forms at normal
// incidence. An orthographic camera looks through a smooth slab at an emitter of radiance E behind it
// (black, index-matched, so nothing is reflected back). Every camera ray meets both faces at normal
// incidence, so with the interface reflectance R = ((n - 1) / (n + 1))^2 and the single-pass
// transmittance A of the slab's interior, the incoherent sum of all internal reflections gives
//   T = (1 - R)^2 A / (1 - R^2 A^2)
// (Born & Wolf; pbrt-v4 section 9.5 for R). A refractive solid (thicknessFactor > 0) absorbs per
// Beer-Lambert, A = attenuationColor^(thickness / attenuationDistance) (KHR_materials_volume); a
// thin-walled slab (thicknessFactor 0) has A = 1 whatever its attenuation.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createWavefrontPathTracingComputeRenderer } from '../../src/pathtracer/index.ts';
import type { WavefrontMaterialInput } from '../../src/scene/types.ts';
import { testDevice } from '../helpers/gpu.ts';
import { box, emitter, slabTransmittance } from './slab-scene.ts';

const size = 16;
const E = [2, 3, 4];
const camera = { type: 'orthographic' as const, position: [0, 0, 4], target: [0, 0, 0], up: [0, 1, 0], orthographicHeight: 1 };

async function renderThrough(material: WavefrontMaterialInput, thickness: number, spp = 64, inner?: { material: WavefrontMaterialInput; thickness: number }): Promise<number[]> {
  const device = await testDevice();
  const slab = box(-thickness / 2, thickness / 2);
  const nested = inner ? [{ ...box(-inner.thickness / 2, inner.thickness / 2, 0.8), material: inner.material }] : [];
  const renderer = await createWavefrontPathTracingComputeRenderer({
    device, width: size, height: size, maxDepth: 24, samplesPerPixel: spp, seed: 3, camera,
    meshes: [{ ...slab, material }, ...nested, emitter(E)],
  });
  try {
    const stats = await renderer.renderFrame();
    assert.equal(stats.invalidSamples, 0);
    const { data } = await renderer.readRadiance();
    const mean = [0, 0, 0];
    for (let p = 0; p < size * size; p++) for (let c = 0; c < 3; c++) mean[c]! += data[4 * p + c]! / (size * size);
    return mean;
  } finally {
    renderer.destroy();
  }
}

const glass: WavefrontMaterialInput = { baseColorFactor: [1, 1, 1], metallicFactor: 0, roughnessFactor: 0, transmissionFactor: 1 };

// Each sample is a chain of Fresnel-chosen delta events: its value is E (times A^k) or 0, so the
// mean of N = 16^2 * 64 samples has a relative standard error below sqrt(R / N) ~ 0.2%: 1% is > 4 sigma.
const TOLERANCE = 0.01;

test('a smooth glass slab (refractive solid, ior 1.5) transmits (1 - R)^2 / (1 - R^2) of the light behind it', async () => {
  const m = await renderThrough({ ...glass, ior: 1.5, thicknessFactor: 0.5 }, 0.5);
  const t = slabTransmittance(1.5, 1);
  for (let c = 0; c < 3; c++) assert.ok(Math.abs(m[c]! - t * E[c]!) <= TOLERANCE * t * E[c]!, `channel ${c}: ${m[c]} vs ${t * E[c]!}`);
  // The closed form differs from no glass at all by 8%: the test can tell.
  assert.ok(t < 0.93);
});

test('a denser smooth slab (ior 2.4) follows the same Fresnel closed form', async () => {
  const m = await renderThrough({ ...glass, ior: 2.4, thicknessFactor: 0.5 }, 0.5);
  const t = slabTransmittance(2.4, 1);
  for (let c = 0; c < 3; c++) assert.ok(Math.abs(m[c]! - t * E[c]!) <= TOLERANCE * t * E[c]!, `channel ${c}: ${m[c]} vs ${t * E[c]!}`);
});

test('Beer-Lambert: a slab of thickness d absorbs attenuationColor^(d / attenuationDistance) per pass', async () => {
  const color = [0.5, 0.7, 0.9];
  const distance = 0.8;
  const d = 0.6;
  const m = await renderThrough({ ...glass, ior: 1.5, thicknessFactor: d, attenuationColor: color, attenuationDistance: distance }, d);
  for (let c = 0; c < 3; c++) {
    const t = slabTransmittance(1.5, color[c]! ** (d / distance));
    assert.ok(Math.abs(m[c]! - t * E[c]!) <= TOLERANCE * t * E[c]!, `channel ${c}: ${m[c]} vs ${t * E[c]!}`);
  }
});

test('thin-walled (thicknessFactor 0): no refraction and no absorption, each face reflects R', async () => {
  const m = await renderThrough({ ...glass, ior: 1.5, thicknessFactor: 0, attenuationColor: [0.2, 0.2, 0.2], attenuationDistance: 0.1 }, 0.5);
  const t = slabTransmittance(1.5, 1);
  for (let c = 0; c < 3; c++) assert.ok(Math.abs(m[c]! - t * E[c]!) <= TOLERANCE * t * E[c]!, `channel ${c}: ${m[c]} vs ${t * E[c]!}`);
});

test('nested media: an index-matched absorbing solid inside a clear one absorbs over its own thickness only, with no Fresnel at the inner faces', async () => {
  // Outer solid: clear glass 1.0 thick. Inner solid: same ior, absorbing, 0.4 thick. The medium stack
  // makes the inner faces index-matched (relative ior 1: no reflection) and restores the outer
  // medium (not vacuum) when the path leaves the inner one; a wrong stack would add reflections at
  // the inner faces and a wrong index at the outer back face.
  const color = [0.3, 0.6, 0.9];
  const d = 0.4;
  const m = await renderThrough({ ...glass, ior: 1.5, thicknessFactor: 1 }, 1, 64, {
    material: { ...glass, ior: 1.5, thicknessFactor: d, attenuationColor: color, attenuationDistance: 1 },
    thickness: d,
  });
  for (let c = 0; c < 3; c++) {
    const t = slabTransmittance(1.5, color[c]! ** d);
    assert.ok(Math.abs(m[c]! - t * E[c]!) <= TOLERANCE * t * E[c]!, `channel ${c}: ${m[c]} vs ${t * E[c]!}`);
  }
});

test('KHR_materials_dispersion: a path through a dispersive slab carries one sampled wavelength whose RGB response averages back to the light colour', async () => {
  // At normal incidence no wavelength is deviated and R barely depends on it (ior 1.5 +- 0.01 at
  // dispersion 1), so the spectral estimate must converge to the non-dispersive closed form: the
  // sampled wavelengths' RGB responses, divided by their pdf, must integrate to white.
  const m = await renderThrough({ ...glass, ior: 1.5, thicknessFactor: 0.5, dispersion: 1 }, 0.5, 256);
  const t = slabTransmittance(1.5, 1);
  for (let c = 0; c < 3; c++) assert.ok(Math.abs(m[c]! - t * E[c]!) <= 0.02 * t * E[c]!, `channel ${c}: ${m[c]} vs ${t * E[c]!}`);
});
