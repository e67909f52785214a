import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createSpectralSamples, dispersiveIor, fraunhoferLinesNm } from '../../src/transport/spectral-samples.ts';
import { beerLambertTransmittance } from '../../src/transport/beer-lambert.ts';
import { GpuRendererError } from '../../src/errors/gpu-renderer-error.ts';

const close = (a: number, b: number, tol: number, message?: string): void => assert.ok(Math.abs(a - b) <= tol, `${message ?? ''} ${a} vs ${b}`);

test('dispersion matches the KHR_materials_dispersion formula and the Abbe number definition', () => {
  for (const [ior, dispersion] of [[1.5, 0.2], [1.7, 1], [2.4, 0.5]]) {
    const V = 20 / dispersion;
    const { F, C, D } = fraunhoferLinesNm;
    // Abbe number definition V = (n_D - 1) / (n_F - n_C), with n_D the authored ior.
    close(dispersiveIor(ior, dispersion, D), ior, 1e-12);
    close((dispersiveIor(ior, dispersion, D) - 1) / (dispersiveIor(ior, dispersion, F) - dispersiveIor(ior, dispersion, C)), V, 1e-9);
    // The extension text's numeric form: n = max(n_d + (n_d - 1) / V * (523655 / lambda^2 - 1.5168), 1).
    const samples = createSpectralSamples({ ior, dispersion, count: 8 });
    assert.equal(samples.length, 8);
    for (const s of samples) {
      const khr = Math.max(ior + ((ior - 1) / V) * (523655 / s.wavelengthNm ** 2 - 1.5168), 1);
      close(s.ior, khr, 2e-4, `lambda=${s.wavelengthNm}`);
    }
    // Normal dispersion: shorter wavelengths bend more.
    for (let i = 1; i < samples.length; i++) assert.ok(samples[i]!.ior < samples[i - 1]!.ior);
    close(samples.reduce((s, x) => s + x.weight, 0), 1, 1e-12);
  }
});

test('without dispersion one sample at lambda_D carries the authored ior with weight 1', () => {
  const samples = createSpectralSamples({ ior: 1.45, dispersion: 0 });
  assert.equal(samples.length, 1);
  assert.equal(samples[0]!.ior, 1.45);
  assert.equal(samples[0]!.weight, 1);
  assert.equal(samples[0]!.wavelengthNm, fraunhoferLinesNm.D);
  assert.throws(() => createSpectralSamples({ ior: 1.5, dispersion: -1 }), (e: unknown) => e instanceof GpuRendererError && e.field === 'dispersion');
});

test('Beer-Lambert: T(attenuationDistance) = attenuationColor, T(0) = 1, multiplicative, infinite distance = none', () => {
  const color = [0.8, 0.5, 0.1];
  const d = 2.5;
  const atD = beerLambertTransmittance(color, d, d);
  color.forEach((c, i) => close(atD[i]!, c, 1e-12));
  assert.deepEqual(beerLambertTransmittance(color, d, 0), [1, 1, 1]);
  assert.deepEqual(beerLambertTransmittance(color, Infinity, 100), [1, 1, 1]);
  // exp(-sigma (a + b)) = exp(-sigma a) exp(-sigma b), with sigma = -ln(c) / d.
  const a = beerLambertTransmittance(color, d, 0.7);
  const b = beerLambertTransmittance(color, d, 1.9);
  const ab = beerLambertTransmittance(color, d, 2.6);
  color.forEach((c, i) => {
    close(ab[i]!, a[i]! * b[i]!, 1e-12);
    close(a[i]!, Math.exp((Math.log(c) / d) * 0.7), 1e-12);
  });
  assert.deepEqual(beerLambertTransmittance([1, 0.5, 0], 1, Infinity), [1, 0, 0]);
  const isField = (field: string) => (e: unknown) => e instanceof GpuRendererError && e.field === field;
  assert.throws(() => beerLambertTransmittance([1, 2, 0], 1, 1), isField('attenuationColor[1]'));
  assert.throws(() => beerLambertTransmittance([1, 1, 1], 0, 1), isField('attenuationDistance'));
  assert.throws(() => beerLambertTransmittance([1, 1, 1], 1, -1), isField('distance'));
});
