import { test } from 'node:test';
import assert from 'node:assert/strict';
import { GpuRendererError } from '../../src/errors/gpu-renderer-error.ts';
import { readStruct } from '../../src/gpu-layout/struct-layout.ts';
import { environmentRadiance } from '../../src/lighting/environment-map.ts';
import { buildEnvironmentSampler, environmentPdf, sampleEnvironment } from '../../src/lighting/environment-sampling.ts';
import {
  buildPortalEnvironmentSampler,
  environmentPortalLayout,
  packPortals,
  portalDirectionToUv,
  portalEnvironmentPdf,
  portalUvToDirection,
  portalWindow,
  samplePortalEnvironment,
  validateEnvironmentPortalMode,
  validateEnvironmentPortals,
  windowIntegral,
  type Portal,
} from '../../src/lighting/portals.ts';
import { add, cross, dot, length, luminance, normalize, scale, sub, type Vec3 } from '../../src/lighting/vec3.ts';
import { chiSquareTest, makeMap, meanAndError, relDiff, rng, uniformSphere } from './helpers.ts';

/** A sky: blue-ish gradient, a bright sun patch high in +X, black below the horizon. */
function skyMap() {
  return makeMap(64, 32, (i, j) => {
    if (j >= 16) return [0, 0, 0];
    if (j >= 4 && j <= 5 && i >= 46 && i <= 47) return [3000, 2800, 2500];
    return [0.5 + 0.05 * j, 0.7 + 0.03 * j, 1.5 - 0.04 * j + 0.1 * Math.sin(i / 5)];
  });
}

// A window in the wall x = 2 (the room is x < 2), 1.2 wide (z) and 1 high (y); outward normal +X.
const windowPortal = (): Portal[] => validateEnvironmentPortals([{ center: [2, 1.5, 0], edgeU: [0, 0, -1.2], edgeV: [0, 1, 0] }]);

test('portal validation and mode', () => {
  const [p] = windowPortal();
  assert.ok(length(sub(p!.z, [1, 0, 0])) < 1e-12);
  assert.deepEqual(p!.corner, [2, 1, 0.6]);
  const check = (fn: () => unknown, field: string) =>
    assert.throws(fn, (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_ENVIRONMENT' && e.field === field);
  check(() => validateEnvironmentPortals({}), 'environmentPortals');
  check(() => validateEnvironmentPortals([{ center: [0, 0, 0], edgeU: [1, 0, 0], edgeV: [1, 1, 0] }]), 'environmentPortals[0].edgeV');
  check(() => validateEnvironmentPortals([{ center: [0, Number.NaN, 0], edgeU: [1, 0, 0], edgeV: [0, 1, 0] }]), 'environmentPortals[0].center[1]');
  check(() => validateEnvironmentPortals([null]), 'environmentPortals[0]');
  check(() => validateEnvironmentPortals([{ center: [0, 0, 0], edgeU: [0, 0, 0], edgeV: [0, 1, 0] }]), 'environmentPortals[0].edgeU');
  assert.equal(validateEnvironmentPortalMode(undefined), 'guide');
  assert.equal(validateEnvironmentPortalMode('guide-and-gate'), 'guide-and-gate');
  check(() => validateEnvironmentPortalMode('gate'), 'environmentPortalMode');
});

test('rectified parametrisation: round trip, Jacobian, and the window is the portal', () => {
  const [portal] = windowPortal();
  const random = rng(1);
  for (let k = 0; k < 300; k++) {
    const u = 0.05 + 0.9 * random();
    const v = 0.05 + 0.9 * random();
    const { direction, jacobian } = portalUvToDirection(portal!, u, v);
    const back = portalDirectionToUv(portal!, direction)!;
    assert.ok(Math.abs(back.u - u) < 1e-12 && Math.abs(back.v - v) < 1e-12);
    const h = 1e-6;
    const du = scale(sub(portalUvToDirection(portal!, u + h, v).direction, portalUvToDirection(portal!, u - h, v).direction), 1 / (2 * h));
    const dv = scale(sub(portalUvToDirection(portal!, u, v + h).direction, portalUvToDirection(portal!, u, v - h).direction), 1 / (2 * h));
    assert.ok(relDiff(length(cross(du, dv)), jacobian) < 1e-6);
  }
  // From a point behind the window, a direction passes through the portal iff its uv is in the window.
  const p: Vec3 = [0.3, 1.1, 0.4];
  const window = portalWindow(portal!, p)!;
  for (let k = 0; k < 2000; k++) {
    const d = uniformSphere(random);
    const uv = portalDirectionToUv(portal!, d);
    const t = (2 - p[0]) / d[0];
    const hit = add(p, scale(d, t));
    const through = d[0] > 0 && Math.abs(hit[2]) <= 0.6 && hit[1] >= 1 && hit[1] <= 2;
    const inWindow = uv !== null && uv.u >= window[0] && uv.u <= window[1] && uv.v >= window[2] && uv.v <= window[3];
    assert.equal(inWindow, through, `direction ${d}`);
  }
  assert.equal(portalWindow(portal!, [3, 1.5, 0]), null, 'outside the room there is no window');
});

test('portal sampling: chi-square against its density, pdf consistency and normalisation', () => {
  const env = buildEnvironmentSampler(skyMap());
  const portals = [...windowPortal(), ...validateEnvironmentPortals([{ center: [0, 3, 0], edgeU: [0.8, 0, 0], edgeV: [0, 0, 0.8] }])];
  const p: Vec3 = [0.5, 1.2, 0.1];
  for (const mode of ['guide', 'guide-and-gate'] as const) {
    const s = buildPortalEnvironmentSampler(env, portals, { mode, resolution: 32 });
    const random = rng(2);
    // pdf consistency.
    for (let k = 0; k < 5000; k++) {
      const x = samplePortalEnvironment(s, p, random(), random(), random());
      assert.ok(x.pdf > 0);
      assert.ok(relDiff(x.pdf, portalEnvironmentPdf(s, p, x.direction)) < 1e-6);
    }
    // Normalisation: integrate the density over the sphere in the environment's own (theta, phi)
    // grid plus, for the portals, over their surfaces (d omega = cos / d^2 dA).
    let throughPortals = 0;
    const m = 300;
    for (const portal of portals) {
      const area = length(portal.edgeU) * length(portal.edgeV);
      for (let a = 0; a < m; a++) {
        for (let b = 0; b < m; b++) {
          const x = add(add(portal.corner, scale(portal.edgeU, (a + 0.5) / m)), scale(portal.edgeV, (b + 0.5) / m));
          const d = sub(x, p);
          const dist = length(d);
          const w = scale(d, 1 / dist);
          const cos = Math.abs(dot(w, portal.z));
          const gatePdf = mode === 'guide-and-gate' ? portalEnvironmentPdf(s, p, w) : portalEnvironmentPdf(s, p, w) - 0.25 * environmentPdf(env, w);
          throughPortals += (gatePdf * cos * area) / (dist * dist * m * m);
        }
      }
    }
    assert.ok(Math.abs(throughPortals - (mode === 'guide-and-gate' ? 1 : 0.75)) < 3e-3, `${mode}: portal mass ${throughPortals}`);
    // Chi-square over the first portal's surface (8 x 8 cells), expected counts by quadrature.
    const n = 100_000;
    const g = 8;
    const portal = portals[0]!;
    const observed = new Float64Array(g * g + 1);
    for (let k = 0; k < n; k++) {
      const x = samplePortalEnvironment(s, p, random(), random(), random());
      const t = dot(sub(portal.corner, p), portal.z) / dot(x.direction, portal.z);
      const hit = t > 0 ? add(p, scale(x.direction, t)) : null;
      const a = hit ? dot(sub(hit, portal.corner), portal.edgeU) / dot(portal.edgeU, portal.edgeU) : -1;
      const b = hit ? dot(sub(hit, portal.corner), portal.edgeV) / dot(portal.edgeV, portal.edgeV) : -1;
      if (a >= 0 && a <= 1 && b >= 0 && b <= 1) observed[Math.min(g - 1, Math.floor(a * g)) * g + Math.min(g - 1, Math.floor(b * g))]++;
      else observed[g * g]++;
    }
    const expected = new Float64Array(g * g + 1);
    const q = 12;
    const area = length(portal.edgeU) * length(portal.edgeV);
    let inside = 0;
    for (let c = 0; c < g * g; c++) {
      const i = Math.floor(c / g);
      const j = c % g;
      let sum = 0;
      for (let a = 0; a < q; a++) {
        for (let b = 0; b < q; b++) {
          const x = add(add(portal.corner, scale(portal.edgeU, (i + (a + 0.5) / q) / g)), scale(portal.edgeV, (j + (b + 0.5) / q) / g));
          const d = sub(x, p);
          const dist = length(d);
          const w = scale(d, 1 / dist);
          sum += (portalEnvironmentPdf(s, p, w) * Math.abs(dot(w, portal.z))) / (dist * dist);
        }
      }
      expected[c] = (n * sum * area) / (g * g * q * q);
      inside += expected[c]!;
    }
    expected[g * g] = n - inside;
    const r = chiSquareTest(observed, expected);
    assert.ok(!r.outsideSupport && r.pValue > 0.001, `${mode}: chi2 ${r.chi2} dof ${r.dof} p ${r.pValue}`);
  }
});

test('irradiance behind a window: the same expected value with and without portals, lower variance with them', () => {
  const map = skyMap();
  const env = buildEnvironmentSampler(map);
  const portals = windowPortal();
  const portal = portals[0]!;
  const p: Vec3 = [0.2, 0.9, 0.3];
  const n: Vec3 = normalize([1, 0.3, 0]);
  // Reference: integral over the window's area of L cos_r cos_w / d^2 (the walls block the rest).
  let reference = 0;
  const m = 600;
  const area = length(portal.edgeU) * length(portal.edgeV);
  for (let a = 0; a < m; a++) {
    for (let b = 0; b < m; b++) {
      const x = add(add(portal.corner, scale(portal.edgeU, (a + 0.5) / m)), scale(portal.edgeV, (b + 0.5) / m));
      const d = sub(x, p);
      const dist = length(d);
      const w = scale(d, 1 / dist);
      reference += (luminance(environmentRadiance(map, w)) * Math.max(0, dot(n, w)) * dot(w, portal.z) * area) / (dist * dist * m * m);
    }
  }
  const visible = (w: Vec3): boolean => {
    if (!(w[0] > 0)) return false;
    const hit = add(p, scale(w, (2 - p[0]) / w[0]));
    return Math.abs(hit[2]) <= 0.6 && hit[1] >= 1 && hit[1] <= 2;
  };
  const estimate = (sample: (random: () => number) => { direction: Vec3; pdf: number; radiance: Vec3 }) => {
    const random = rng(5);
    const values = new Float64Array(200_000);
    for (let k = 0; k < values.length; k++) {
      const s = sample(random);
      values[k] = s.pdf > 0 && visible(s.direction) ? (luminance(s.radiance) * Math.max(0, dot(n, s.direction))) / s.pdf : 0;
    }
    return meanAndError(values);
  };
  const plain = estimate((r) => sampleEnvironment(env, r(), r()));
  const results: Record<string, { mean: number; stderr: number }> = { none: plain };
  for (const mode of ['guide', 'guide-and-gate'] as const) {
    const s = buildPortalEnvironmentSampler(env, portals, { mode });
    results[mode] = estimate((r) => samplePortalEnvironment(s, p, r(), r(), r()));
  }
  for (const [name, { mean, stderr }] of Object.entries(results)) {
    assert.ok(Math.abs(mean - reference) < 4 * stderr + 2e-3 * reference, `${name}: ${mean} +- ${stderr} vs ${reference}`);
  }
  const varianceRatio = (results.none!.stderr / results['guide-and-gate']!.stderr) ** 2;
  console.log(
    `portal irradiance: reference ${reference.toFixed(4)}; no portals ${results.none!.mean.toFixed(4)} +- ${results.none!.stderr.toFixed(4)}, guide ${results.guide!.mean.toFixed(4)} +- ${results.guide!.stderr.toFixed(4)}, guide-and-gate ${results['guide-and-gate']!.mean.toFixed(4)} +- ${results['guide-and-gate']!.stderr.toFixed(4)}; variance ratio (none / gate) ${varianceRatio.toFixed(1)}, (none / guide) ${((results.none!.stderr / results.guide!.stderr) ** 2).toFixed(1)}`,
  );
  assert.ok(varianceRatio > 5);
});

test('portal tables pack into EnvironmentPortal records and one f32 array', () => {
  const env = buildEnvironmentSampler(skyMap());
  const s = buildPortalEnvironmentSampler(env, windowPortal(), { resolution: 16 });
  const { records, data } = packPortals(s);
  assert.equal(environmentPortalLayout.size, 64);
  const rec = readStruct(environmentPortalLayout, new DataView(records), 0);
  assert.equal(rec.resolution, 16);
  assert.equal(rec.funcOffset, 0);
  assert.equal(rec.satOffset, 256);
  assert.equal(data.length, 256 + 17 * 17);
  // The SAT's last entry is the integral of the whole density over [0, 1]^2.
  const d = s.distributions[0]!;
  assert.ok(relDiff(data[256 + 17 * 17 - 1]!, windowIntegral(d, 0, 1, 0, 1)) < 1e-6);
  // f32 SAT precision: the relative error of window integrals from the rounded table, reported.
  let worst = 0;
  const random = rng(9);
  for (let k = 0; k < 1000; k++) {
    const a = random();
    const b = a + 0.2 * random();
    const c = random();
    const e = c + 0.2 * random();
    const exact = windowIntegral(d, a, Math.min(1, b), c, Math.min(1, e));
    const rounded = windowIntegral({ ...d, sat: Float64Array.from(d.sat, Math.fround) }, a, Math.min(1, b), c, Math.min(1, e));
    if (exact > 0) worst = Math.max(worst, relDiff(exact, rounded));
  }
  console.log(`portal SAT in f32: worst relative error of a window integral ${worst.toExponential(2)} (16 x 16)`);
  assert.ok(worst < 1e-3);
});
