// The KHR material factors flattened under their glTF names on a scene's material: accepted with the
// extensions' defaults and ranges, and refused with a typed error naming the field otherwise.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { GpuRendererError } from '../../src/errors/index.ts';
import { normalizeMaterial } from '../../src/scene/material.ts';
import type { WavefrontMaterialInput } from '../../src/scene/types.ts';

function refuses(material: Record<string, unknown>, field: string): void {
  assert.throws(
    () => normalizeMaterial(material as WavefrontMaterialInput, 'materials[3]'),
    (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_MATERIAL' && e.field === `materials[3].${field}`,
    `${JSON.stringify(material)} should be refused naming materials[3].${field}`,
  );
}

test('every KHR factor is accepted under its glTF name and lands in the normalised material', () => {
  const m = normalizeMaterial({
    transmissionFactor: 0.8, thicknessFactor: 0.5, attenuationColor: [0.5, 0.6, 0.7], attenuationDistance: 2, ior: 1.45,
    specularFactor: 0.7, specularColorFactor: [1, 0.9, 0.8], clearcoatFactor: 0.6, clearcoatRoughnessFactor: 0.2,
    sheenColorFactor: [0.3, 0.2, 0.1], sheenRoughnessFactor: 0.4, dispersion: 0.5, iridescenceFactor: 0.9, iridescenceIor: 1.4,
    iridescenceThicknessMinimum: 150, iridescenceThicknessMaximum: 420, anisotropyStrength: 0.6, anisotropyRotation: 1.2,
    diffuseTransmissionFactor: 0.25, diffuseTransmissionColorFactor: [0.9, 0.8, 0.1], emissiveFactor: [1, 0.5, 0.25], emissiveStrength: 8,
  }, 'materials[0]');
  assert.equal(m.ior, 1.45);
  assert.deepEqual(m.emission, [8, 4, 2]);
  assert.equal(m.transmission?.factor, 0.8);
  assert.equal(m.volume?.thicknessFactor, 0.5);
  assert.deepEqual(m.volume?.attenuationColor, [0.5, 0.6, 0.7]);
  assert.equal(m.volume?.attenuationDistance, 2);
  assert.equal(m.clearcoat?.factor, 0.6);
  assert.equal(m.clearcoat?.roughnessFactor, 0.2);
  assert.deepEqual(m.sheen?.colorFactor, [0.3, 0.2, 0.1]);
  assert.equal(m.sheen?.roughnessFactor, 0.4);
  assert.equal(m.iridescence?.ior, 1.4);
  assert.equal(m.dispersion, 0.5);
  assert.ok(m.specular && m.anisotropy && m.diffuseTransmission && m.iridescence);
});

test('materials without extension factors carry no extension blocks (their features compile out)', () => {
  const m = normalizeMaterial({ baseColorFactor: [0.5, 0.5, 0.5], roughnessFactor: 0.3 }, 'materials[0]');
  for (const key of ['specular', 'transmission', 'volume', 'clearcoat', 'sheen', 'iridescence', 'anisotropy', 'diffuseTransmission', 'dispersion'] as const) {
    assert.equal(m[key], undefined, key);
  }
  // Zero factors (the extensions' defaults) are the same as absent.
  const z = normalizeMaterial({ transmissionFactor: 0, clearcoatFactor: 0, sheenColorFactor: [0, 0, 0], iridescenceFactor: 0 }, 'materials[0]');
  assert.equal(z.transmission, undefined);
  assert.equal(z.clearcoat, undefined);
  assert.equal(z.sheen, undefined);
  assert.equal(z.iridescence, undefined);
});

test('bad KHR factors are typed errors naming the field', () => {
  refuses({ transmissionFactor: 1.5 }, 'transmissionFactor');
  refuses({ transmissionFactor: -0.1 }, 'transmissionFactor');
  refuses({ thicknessFactor: -1 }, 'thicknessFactor');
  refuses({ attenuationColor: [0.5, 2, 0.5] }, 'attenuationColor[1]');
  refuses({ attenuationColor: [0.5, 0.5] }, 'attenuationColor');
  refuses({ attenuationDistance: 0 }, 'attenuationDistance');
  refuses({ attenuationDistance: -2 }, 'attenuationDistance');
  refuses({ ior: 0.5 }, 'ior');
  refuses({ ior: Number.NaN }, 'ior');
  refuses({ specularFactor: 2 }, 'specularFactor');
  refuses({ specularColorFactor: [1, -1, 1] }, 'specularColorFactor[1]');
  refuses({ clearcoatFactor: 'high' }, 'clearcoatFactor');
  refuses({ clearcoatRoughnessFactor: 1.1 }, 'clearcoatRoughnessFactor');
  refuses({ sheenColorFactor: [0, 0, 2] }, 'sheenColorFactor[2]');
  refuses({ sheenRoughnessFactor: -0.5 }, 'sheenRoughnessFactor');
  refuses({ dispersion: -1 }, 'dispersion');
  refuses({ iridescenceFactor: 3 }, 'iridescenceFactor');
  refuses({ iridescenceIor: 0.9 }, 'iridescenceIor');
  refuses({ iridescenceThicknessMinimum: -5 }, 'iridescenceThicknessMinimum');
  refuses({ anisotropyStrength: 1.5 }, 'anisotropyStrength');
  refuses({ anisotropyRotation: Number.POSITIVE_INFINITY }, 'anisotropyRotation');
  refuses({ diffuseTransmissionFactor: 2 }, 'diffuseTransmissionFactor');
  refuses({ diffuseTransmissionColorFactor: [1, 1, 1.2] }, 'diffuseTransmissionColorFactor[2]');
  refuses({ emissiveStrength: -1 }, 'emissiveStrength');
});
