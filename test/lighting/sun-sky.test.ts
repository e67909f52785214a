import { test } from 'node:test';
import assert from 'node:assert/strict';
import { GpuRendererError } from '../../src/errors/gpu-renderer-error.ts';
import { environmentRadiance } from '../../src/lighting/environment-map.ts';
import { buildEnvironmentSampler, environmentPdf, sampleEnvironment } from '../../src/lighting/environment-sampling.ts';
import { clearSkyRadiance, createEnvironmentLighting, validateEnvironmentLighting } from '../../src/lighting/environment-lighting.ts';
import { createHosekWilkieSky } from '../../src/lighting/hosek-wilkie.ts';
import * as data from '../../src/lighting/hosek-wilkie-rgb-data.ts';
import { cieXyzMatching, solarDiscRadiance } from '../../src/lighting/solar-radiance.ts';
import { sampleSun, sunPdf, sunRadiance, sunSolidAngle, type SunLight } from '../../src/lighting/sun-light.ts';
import { add, dot, luminance, normalize, orthonormalBasis, scale, sub, type Vec3 } from '../../src/lighting/vec3.ts';
import { chiSquareTest, meanAndError, rng, uniformSphere } from './helpers.ts';

const deg = (x: number) => (x * Math.PI) / 180;

function sunAt(elevationDeg: number, azimuthDeg: number): Vec3 {
  return [Math.cos(deg(elevationDeg)) * Math.cos(deg(azimuthDeg)), Math.sin(deg(elevationDeg)), Math.cos(deg(elevationDeg)) * Math.sin(deg(azimuthDeg))];
}

test('Hosek-Wilkie tables have the published sizes', () => {
  for (const t of [data.HOSEK_WILKIE_RGB_1, data.HOSEK_WILKIE_RGB_2, data.HOSEK_WILKIE_RGB_3]) assert.equal(t.length, 2 * 10 * 6 * 9);
  for (const t of [data.HOSEK_WILKIE_RGB_RADIANCE_1, data.HOSEK_WILKIE_RGB_RADIANCE_2, data.HOSEK_WILKIE_RGB_RADIANCE_3]) assert.equal(t.length, 2 * 10 * 6);
});

test('sky radiance is finite and non-negative over the dome for the whole parameter range', () => {
  const random = rng(1);
  for (const turbidity of [1, 2.5, 5, 7.3, 10]) {
    for (const albedo of [0, 0.4, 1]) {
      for (const elevation of [0, 1, 5, 20, 45, 70, 90]) {
        const sun = sunAt(elevation, 30);
        const sky = createHosekWilkieSky(turbidity, [albedo, albedo, albedo], deg(elevation));
        for (let k = 0; k < 200; k++) {
          const d = uniformSphere(random);
          d[1] = Math.abs(d[1]);
          const l = clearSkyRadiance(sky, sun, d);
          for (const c of l) assert.ok(Number.isFinite(c) && c >= 0, `T ${turbidity} albedo ${albedo} elevation ${elevation}: ${l}`);
        }
      }
    }
  }
});

test('sky radiance is symmetric about the sun\'s vertical plane and brighter towards the sun', () => {
  const sun = sunAt(25, 70);
  const sky = createHosekWilkieSky(3, [0.3, 0.3, 0.3], deg(25));
  // The vertical plane through the sun has normal m = normalize(sun x up); mirror d across it.
  const m = normalize([sun[2], 0, -sun[0]]);
  const random = rng(2);
  for (let k = 0; k < 500; k++) {
    const d = uniformSphere(random);
    d[1] = Math.abs(d[1]);
    const mirrored = sub(d, scale(m, 2 * dot(d, m)));
    const a = clearSkyRadiance(sky, sun, d);
    const b = clearSkyRadiance(sky, sun, mirrored);
    for (let c = 0; c < 3; c++) assert.ok(Math.abs(a[c] - b[c]) <= 1e-9 * Math.max(a[c], 1), `asymmetric at ${d}`);
  }
  for (const elevation of [10, 25, 40, 60, 80]) {
    const towards = clearSkyRadiance(sky, sun, sunAt(elevation, 70));
    const away = clearSkyRadiance(sky, sun, sunAt(elevation, 250));
    assert.ok(luminance(towards) > luminance(away), `elevation ${elevation}`);
  }
});

test('physical scale: CIE y-bar, solar illuminance and clear-sky luminance match published magnitudes', () => {
  let yBar = 0;
  for (let l = 360; l <= 830; l++) yBar += cieXyzMatching(l)[1];
  assert.ok(Math.abs(yBar / 106.857 - 1) < 0.005, `integral of y-bar ${yBar}`);
  const omega = 2 * Math.PI * (1 - Math.cos(deg(0.533 / 2)));
  // Extraterrestrial solar illuminance is about 128 klux (solar constant 1361 W/m^2).
  const toa = luminance(solarDiscRadiance(Math.PI / 2, 1, 0)) * omega;
  assert.ok(toa > 120_000 && toa < 135_000, `top of atmosphere ${toa} lux`);
  // Direct normal illuminance of a high sun through a clear atmosphere: about 80-110 klux.
  const direct = luminance(solarDiscRadiance(deg(60), 3)) * omega;
  assert.ok(direct > 75_000 && direct < 110_000, `direct normal ${direct} lux`);
  const noon = createEnvironmentLighting({ preset: 'noon', width: 128, height: 64 });
  const diffuse = noon.horizontalIlluminance - luminance(noon.sun!.radiance) * sunSolidAngle(noon.sun!) * noon.sun!.direction[1];
  assert.ok(diffuse > 10_000 && diffuse < 30_000, `clear-sky diffuse horizontal illuminance ${diffuse} lux`);
  const zenith = luminance(environmentRadiance(noon.map, [0, 1, 0]));
  assert.ok(zenith > 2000 && zenith < 10_000, `zenith luminance ${zenith} nits`);
  // A low sun is redder than a high one.
  const low = solarDiscRadiance(deg(5), 3);
  const high = solarDiscRadiance(deg(70), 3);
  assert.ok(low[0] / low[2] > 2 * (high[0] / high[2]));
});

function testSun(limbDarkening: boolean): SunLight {
  return { direction: normalize([0.3, 0.8, -0.2]), oneMinusCosThetaMax: 2 * Math.sin(deg(0.265) / 2) ** 2, radiance: [3e9, 2e9, 1e9], limbDarkening };
}

test('sun disc: exact solid angle, uniform cone sampling (chi-square), consistent pdf', () => {
  const sun = testSun(false);
  // 2 pi (1 - cos 0.265 deg), by the series 2 pi (x^2/2 - x^4/24 + x^6/720).
  const x = deg(0.265);
  assert.ok(Math.abs(sunSolidAngle(sun) / (2 * Math.PI * (x ** 2 / 2 - x ** 4 / 24 + x ** 6 / 720)) - 1) < 1e-12);
  const { t, b } = orthonormalBasis(sun.direction);
  const g = 10;
  const observed = new Float64Array(g * g);
  const random = rng(3);
  const n = 100_000;
  for (let k = 0; k < n; k++) {
    const s = sampleSun(sun, random(), random());
    assert.equal(s.pdf, 1 / sunSolidAngle(sun));
    assert.equal(sunPdf(sun, s.direction), s.pdf);
    const omc = dot(sub(s.direction, sun.direction), sub(s.direction, sun.direction)) / 2;
    const phi = Math.atan2(dot(s.direction, b), dot(s.direction, t)) + Math.PI;
    observed[Math.min(g - 1, Math.floor((omc / sun.oneMinusCosThetaMax) * g)) * g + Math.min(g - 1, Math.floor((phi / (2 * Math.PI)) * g))]++;
  }
  const r = chiSquareTest(observed, new Float64Array(g * g).fill(n / (g * g)));
  assert.ok(r.pValue > 0.001, `chi2 ${r.chi2} p ${r.pValue}`);
  // Just outside the disc: no density, no radiance.
  const outside = normalize(add(sun.direction, scale(t, Math.tan(deg(0.27)))));
  assert.equal(sunPdf(sun, outside), 0);
  assert.deepEqual(sunRadiance(sun, outside), [0, 0, 0]);
  const inside = normalize(add(sun.direction, scale(t, Math.tan(deg(0.26)))));
  assert.ok(sunPdf(sun, inside) > 0);
});

test('limb darkening keeps the disc\'s mean radiance (quadrature) and darkens the rim', () => {
  const sun = testSun(true);
  const { t } = orthonormalBasis(sun.direction);
  // Mean over the cone, midpoint rule in s = (1 - cos) / (1 - cos max), uniform in solid angle.
  let mean = 0;
  const m = 10_000;
  for (let k = 0; k < m; k++) {
    const s = sampleSun(sun, (k + 0.5) / m, 0.25);
    mean += s.radiance[0] / m;
  }
  assert.ok(Math.abs(mean / sun.radiance[0] - 1) < 1e-6, `mean ${mean / sun.radiance[0]}`);
  const centre = sunRadiance(sun, sun.direction)[0];
  const rim = sunRadiance(sun, normalize(add(sun.direction, scale(t, Math.tan(deg(0.2649))))))[0];
  assert.ok(Math.abs(centre / sun.radiance[0] - 1.25) < 1e-9);
  assert.ok(rim < 0.55 * sun.radiance[0]);
});

test('overcast, studio and ground: CIE distribution, illuminance, neutrality', () => {
  const overcast = createEnvironmentLighting({ preset: 'overcast', width: 256, height: 128 });
  assert.equal(overcast.sun, null);
  assert.ok(Math.abs(overcast.horizontalIlluminance / 10_000 - 1) < 0.005, `E_h ${overcast.horizontalIlluminance}`);
  const lz = 10_000 / ((7 * Math.PI) / 9);
  // Texel centres of rows 0 and H/2 - 1: L(theta) = L_z (1 + 2 cos theta) / 3.
  for (const j of [0, 20, 63]) {
    const v = (j + 0.5) / 128;
    const mean = [0, 1, 2].map((c) => overcast.map.data[4 * (j * 256 + 10) + c]!);
    const expected = (lz * (1 + 2 * Math.cos(Math.PI * v))) / 3;
    assert.ok(Math.abs(mean[1]! / expected - 1) < 2e-3, `row ${j}: ${mean[1]} vs ${expected}`);
  }
  // Ground (rows below the horizon): albedo x E_h / pi.
  const groundTexel = overcast.map.data[4 * (100 * 256 + 7) + 1]!;
  assert.ok(Math.abs(groundTexel / ((0.3 * overcast.horizontalIlluminance) / Math.PI) - 1) < 1e-3);
  const studio = createEnvironmentLighting({ preset: 'studio', width: 256, height: 128 });
  let max = 0;
  for (let k = 0; k < studio.map.data.length; k += 4) {
    assert.equal(studio.map.data[k], studio.map.data[k + 1]);
    assert.equal(studio.map.data[k + 1], studio.map.data[k + 2]);
    max = Math.max(max, studio.map.data[k]!);
  }
  assert.equal(max, 2000);
  assert.ok(studio.suggestedExposure > 0 && Number.isFinite(studio.suggestedExposure));
});

test('sun and sky combined by MIS with cosine sampling reproduce the horizontal illuminance', () => {
  const sky = createEnvironmentLighting({ preset: 'clear', sunDirection: sunAt(35, 10), turbidity: 2.5, width: 128, height: 64 });
  const sun = sky.sun!;
  const sampler = buildEnvironmentSampler(sky.map);
  const n: Vec3 = [0, 1, 0];
  const radiance = (d: Vec3) => luminance(environmentRadiance(sky.map, d)) + luminance(sunRadiance(sun, d));
  const lightPdf = (d: Vec3) => 0.5 * environmentPdf(sampler, d) + 0.5 * sunPdf(sun, d);
  const random = rng(4);
  const values = new Float64Array(100_000);
  for (let k = 0; k < values.length; k++) {
    // Light strategy: the environment or the sun, 50 / 50.
    const u = random();
    const ls = u < 0.5 ? sampleEnvironment(sampler, random(), random()) : sampleSun(sun, random(), random());
    let x = 0;
    const cosL = Math.max(0, dot(n, ls.direction));
    if (ls.pdf > 0 && cosL > 0) x += (radiance(ls.direction) * cosL) / (lightPdf(ls.direction) + cosL / Math.PI);
    // BSDF strategy: cosine-weighted hemisphere.
    const r = Math.sqrt(random());
    const phi = 2 * Math.PI * random();
    const d: Vec3 = [r * Math.cos(phi), Math.sqrt(Math.max(0, 1 - r * r)), r * Math.sin(phi)];
    x += (radiance(d) * d[1]) / (lightPdf(d) + d[1] / Math.PI);
    values[k] = x;
  }
  const { mean, stderr } = meanAndError(values);
  // The map integral by texel midpoints and by bilinear lookups differ by well under 0.5 %.
  assert.ok(Math.abs(mean - sky.horizontalIlluminance) < 4 * stderr + 0.005 * sky.horizontalIlluminance, `${mean} +- ${stderr} vs ${sky.horizontalIlluminance}`);
  assert.ok(stderr < 0.01 * mean);
});

test('environmentLighting validation names the field', () => {
  const check = (input: unknown, field: string) =>
    assert.throws(() => validateEnvironmentLighting(input), (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_ENVIRONMENT' && e.field === field);
  check({ preset: 'dusk' }, 'environmentLighting.preset');
  check({ sunDirection: [0, -1, 0] }, 'environmentLighting.sunDirection');
  check({ sunDirection: [0, 0, 0] }, 'environmentLighting.sunDirection');
  check({ turbidity: 0.5 }, 'environmentLighting.turbidity');
  check({ turbidity: Number.NaN }, 'environmentLighting.turbidity');
  check({ groundAlbedo: 1.5 }, 'environmentLighting.groundAlbedo');
  check({ groundAlbedo: [0.1, -0.1, 0.2] }, 'environmentLighting.groundAlbedo[1]');
  check({ sunColor: [1, 1, -1] }, 'environmentLighting.sunColor[2]');
  check({ sunIntensity: -1 }, 'environmentLighting.sunIntensity');
  check({ sunAngularDiameterDegrees: 0 }, 'environmentLighting.sunAngularDiameterDegrees');
  check({ width: 3 }, 'environmentLighting.width');
  check(7, 'environmentLighting');
  // The overcast and studio presets do not need the sun above the horizon.
  assert.equal(validateEnvironmentLighting({ preset: 'studio', sunDirection: [0, -1, 0] }).preset, 'studio');
  assert.equal(createEnvironmentLighting({ preset: 'noon', sunIntensity: 0, width: 8, height: 4 }).sun, null);
});
