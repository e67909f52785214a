import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readStruct } from '../../src/gpu-layout/struct-layout.ts';
import { validateAreaLight } from '../../src/lighting/area-lights.ts';
import type { EmissiveTriangleInput } from '../../src/lighting/emissive-lights.ts';
import { lightBoundsImportance, unionCones } from '../../src/lighting/light-bounds.ts';
import { buildLightSampler, lightPmf, sampleLight, triangleLightBounds, type LightRef } from '../../src/lighting/light-sampler.ts';
import { LIGHT_TREE_NONE, lightTreeNodeLayout, lightTreePmf, sampleLightTree } from '../../src/lighting/light-tree.ts';
import { validatePunctualLight } from '../../src/lighting/punctual-lights.ts';
import { add, cross, dot, length, luminance, normalize, scale, sub, type Vec3 } from '../../src/lighting/vec3.ts';
import { chiSquareTest, relDiff, rng, uniformSphere } from './helpers.ts';

function randomTriangles(count: number, random: () => number, spread: number, yMin: number, yMax: number, size: number): EmissiveTriangleInput[] {
  const out: EmissiveTriangleInput[] = [];
  for (let i = 0; i < count; i++) {
    const c: Vec3 = [(random() - 0.5) * spread, yMin + (yMax - yMin) * random(), (random() - 0.5) * spread];
    const s = size * (0.3 + random());
    const v0 = add(c, scale(uniformSphere(random), s));
    const v1 = add(c, scale(uniformSphere(random), s));
    const v2 = add(c, scale(uniformSphere(random), s));
    const area = length(cross(sub(v1, v0), sub(v2, v0))) / 2;
    out.push({ triangle: i, v0, v1, v2, area, emission: [0.5 + random(), 0.5 + random(), 0.5 + random()], doubleSided: random() < 0.2 });
  }
  return out;
}

function mixedScene(seed: number) {
  const random = rng(seed);
  const triangles = randomTriangles(150, random, 20, -5, 5, 0.5);
  const areaLights = [
    validateAreaLight({ type: 'rectangle', center: [2, 4, 0], edgeU: [1, 0, 0], edgeV: [0, 0, 1], emission: [5, 5, 5] }),
    validateAreaLight({ type: 'disk', center: [-3, 1, 2], normal: [1, 0, 0], radius: 0.5, twoSided: true }),
    validateAreaLight({ type: 'sphere', center: [0, -2, -4], radius: 0.3, emission: [20, 10, 5] }),
  ];
  const punctualLights = [
    validatePunctualLight({ type: 'point', position: [1, 1, 1], intensity: 30 }),
    validatePunctualLight({ type: 'spot', position: [-1, 3, 0], direction: [0, -1, 0], intensity: 100, innerConeAngle: 0.2, outerConeAngle: 0.5 }),
    validatePunctualLight({ type: 'directional', direction: [0, -1, 0], intensity: 2 }),
  ];
  return { triangles, areaLights, punctualLights };
}

function allRefs(t: number, a: number, p: number): LightRef[] {
  return [
    ...Array.from({ length: t }, (_, index) => ({ kind: 'triangle' as const, index })),
    ...Array.from({ length: a }, (_, index) => ({ kind: 'area' as const, index })),
    ...Array.from({ length: p }, (_, index) => ({ kind: 'punctual' as const, index })),
  ];
}

test('cone union contains both cones', () => {
  const random = rng(1);
  for (let k = 0; k < 500; k++) {
    const wa = uniformSphere(random);
    const wb = uniformSphere(random);
    const ca = Math.cos(random() * Math.PI);
    const cb = Math.cos(random() * Math.PI);
    const u = unionCones(wa, ca, wb, cb);
    // Every direction inside either cone is inside the union (checked on random directions).
    for (let j = 0; j < 50; j++) {
      const d = uniformSphere(random);
      if (dot(d, wa) >= ca || dot(d, wb) >= cb) assert.ok(dot(d, u.axis) >= u.cosTheta - 1e-9, `direction outside the union cone`);
    }
  }
});

test('importance is conservative: zero only for emitters facing away from the point', () => {
  const random = rng(2);
  const triangles = randomTriangles(300, random, 6, -3, 3, 0.4);
  for (let k = 0; k < 300; k++) {
    const p: Vec3 = [(random() - 0.5) * 8, (random() - 0.5) * 8, (random() - 0.5) * 8];
    for (const t of triangles) {
      const b = triangleLightBounds(t);
      if (lightBoundsImportance(b, p, [0, 0, 0]) > 0) continue;
      // Then no vertex may see the front face (nor either face of a two-sided triangle).
      if (t.doubleSided) assert.fail('a two-sided triangle had zero importance');
      for (const v of [t.v0, t.v1, t.v2]) assert.ok(dot(b.axis, sub(p, v)) <= 1e-9, 'zero importance for a lit point');
    }
  }
});

test('light tree: pmfs over all lights sum to 1, sampling returns lightPmf, and the layout round-trips', () => {
  const scene = mixedScene(3);
  const sampler = buildLightSampler({ ...scene, environment: true, sun: true });
  assert.equal(sampler.infinite.length, 3);
  const refs = allRefs(scene.triangles.length, scene.areaLights.length, scene.punctualLights.length);
  const random = rng(4);
  for (let k = 0; k < 40; k++) {
    const p: Vec3 = [(random() - 0.5) * 20, (random() - 0.5) * 10, (random() - 0.5) * 20];
    const n = k % 4 === 0 ? ([0, 0, 0] as Vec3) : uniformSphere(random);
    let total = 0;
    for (const r of refs) total += lightPmf(sampler, p, n, r);
    total += lightPmf(sampler, p, n, { kind: 'environment', index: 0 }) + lightPmf(sampler, p, n, { kind: 'sun', index: 0 });
    assert.ok(Math.abs(total - 1) < 1e-9, `sum of pmfs ${total}`);
    for (let j = 0; j < 200; j++) {
      const s = sampleLight(sampler, p, n, random());
      assert.ok(s !== null);
      assert.ok(s.pmf > 0);
      assert.ok(relDiff(s.pmf, lightPmf(sampler, p, n, s)) < 1e-9, `${s.kind} ${s.index}: ${s.pmf} vs ${lightPmf(sampler, p, n, s)}`);
    }
  }
  // Node records: depth-first, parents and leaves consistent with the in-memory tree.
  const view = new DataView(sampler.nodes);
  assert.equal(sampler.nodes.byteLength, sampler.tree.nodes.length * 64);
  sampler.tree.nodes.forEach((node, i) => {
    const rec = readStruct(lightTreeNodeLayout, view, i);
    assert.equal(rec.childOrLight, node.childOrLight);
    assert.equal(rec.parent, node.parent);
    assert.equal((rec.flags as number) & 1, node.leaf ? 1 : 0);
    if (!node.leaf) {
      assert.equal(sampler.tree.nodes[i + 1]!.parent, i);
      assert.equal(sampler.tree.nodes[node.childOrLight]!.parent, i);
    } else {
      assert.equal(sampler.tree.lightToLeaf[node.childOrLight], i);
    }
  });
  assert.equal(sampler.tree.nodes[0]!.parent, LIGHT_TREE_NONE);
});

test('light tree sampling frequencies match the pmf (chi-square)', () => {
  const scene = mixedScene(5);
  const sampler = buildLightSampler(scene);
  const count = scene.triangles.length + scene.areaLights.length + scene.punctualLights.length;
  const random = rng(6);
  for (const [p, n] of [
    [[0.5, 0.2, -0.3], [0, 1, 0]],
    [[8, 3, 8], [0, 0, 0]],
  ] as [Vec3, Vec3][]) {
    const expectedP = new Float64Array(count);
    for (let g = 0; g < count; g++) expectedP[g] = lightTreePmf(sampler.tree, p, n, g);
    const samples = 200_000;
    const observed = new Float64Array(count);
    for (let k = 0; k < samples; k++) {
      const s = sampleLightTree(sampler.tree, p, n, random());
      assert.ok(s !== null);
      observed[s.light]++;
    }
    const r = chiSquareTest(observed, expectedP.map((x) => x * samples));
    assert.ok(!r.outsideSupport && r.pValue > 0.001, `chi2 ${r.chi2} dof ${r.dof} p ${r.pValue}`);
  }
});

test('single light, empty tree and unreachable lights', () => {
  const one = buildLightSampler({ punctualLights: [validatePunctualLight({ type: 'point', position: [0, 1, 0], intensity: 1 })] });
  assert.deepEqual(sampleLight(one, [0, 0, 0], [0, 1, 0], 0.7), { kind: 'punctual', index: 0, pmf: 1 });
  assert.equal(lightPmf(one, [0, 0, 0], [0, 1, 0], { kind: 'punctual', index: 0 }), 1);
  assert.equal(sampleLight(buildLightSampler({}), [0, 0, 0], [0, 1, 0], 0.5), null);
  // A one-sided rectangle facing away from the point next to one facing it: the first is never chosen.
  const away = validateAreaLight({ type: 'rectangle', center: [0, 2, 0], edgeU: [1, 0, 0], edgeV: [0, 0, -1] });
  const facing = validateAreaLight({ type: 'rectangle', center: [3, 2, 0], edgeU: [1, 0, 0], edgeV: [0, 0, 1] });
  const two = buildLightSampler({ areaLights: [away, facing] });
  assert.equal(lightPmf(two, [0, 0, 0], [0, 1, 0], { kind: 'area', index: 0 }), 0);
  assert.equal(lightPmf(two, [0, 0, 0], [0, 1, 0], { kind: 'area', index: 1 }), 1);
  for (const u of [0, 0.3, 0.99]) assert.deepEqual(sampleLight(two, [0, 0, 0], [0, 1, 0], u), { kind: 'area', index: 1, pmf: 1 });
  // Alone, it is still chosen (pmfs always sum to 1); its sample simply contributes nothing.
  assert.equal(lightPmf(buildLightSampler({ areaLights: [away] }), [0, 0, 0], [0, 1, 0], { kind: 'area', index: 0 }), 1);
});

/** A 16-point quadrature of a triangle: centroids of its 4 x 4 subdivision... midpoints of the 16 sub-triangles. */
function triangleQuadrature(t: EmissiveTriangleInput): Vec3[] {
  const pts: Vec3[] = [];
  const m = 4;
  for (let i = 0; i < m; i++) {
    for (let j = 0; j < m - i; j++) {
      const up = [(i + 1 / 3) / m, (j + 1 / 3) / m];
      pts.push(bary(t, up[0]!, up[1]!));
      if (i + j < m - 1) pts.push(bary(t, (i + 2 / 3) / m, (j + 2 / 3) / m));
    }
  }
  return pts;
}

function bary(t: EmissiveTriangleInput, b1: number, b2: number): Vec3 {
  return add(add(scale(t.v0, 1 - b1 - b2), scale(t.v1, b1)), scale(t.v2, b2));
}

test('10,000 emissive triangles: the light tree has far lower direct-lighting variance than power-proportional selection', () => {
  const random = rng(10);
  const triangles = randomTriangles(10_000, random, 100, 0.5, 10, 0.3);
  const started = performance.now();
  const sampler = buildLightSampler({ triangles });
  const buildMs = performance.now() - started;
  const p: Vec3 = [-30, 0, 10];
  const n: Vec3 = [0, 1, 0];
  // Per triangle, with uniform area sampling: E_i = A_i mean(f), S_i = E[(f / pdf_A)^2] = A_i^2 mean(f^2),
  // f(x) = L cos_r cos_l / d^2 (front faces only; every triangle lies above the tangent plane).
  const e = new Float64Array(triangles.length);
  const s2 = new Float64Array(triangles.length);
  triangles.forEach((t, i) => {
    const nl = normalize(cross(sub(t.v1, t.v0), sub(t.v2, t.v0)));
    const pts = triangleQuadrature(t);
    let f1 = 0;
    let f2 = 0;
    for (const x of pts) {
      const d = sub(p, x);
      const dist2 = dot(d, d);
      const w = scale(d, 1 / Math.sqrt(dist2));
      const cosL = t.doubleSided ? Math.abs(dot(nl, w)) : Math.max(0, dot(nl, w));
      const f = (luminance(t.emission) * Math.max(0, -dot(n, w)) * cosL) / dist2;
      f1 += f;
      f2 += f * f;
    }
    e[i] = (t.area * f1) / pts.length;
    s2[i] = (t.area * t.area * f2) / pts.length;
  });
  const power = triangles.map((t) => luminance(t.emission) * t.area * (t.doubleSided ? 2 : 1));
  const totalPower = power.reduce((a, b) => a + b, 0);
  let reference = 0;
  let secondTree = 0;
  let secondPower = 0;
  for (let i = 0; i < triangles.length; i++) {
    reference += e[i]!;
    const pt = lightTreePmf(sampler.tree, p, n, i);
    if (e[i]! > 0) assert.ok(pt > 0, `triangle ${i} contributes but has pmf 0`);
    if (pt > 0) secondTree += s2[i]! / pt;
    secondPower += s2[i]! / (power[i]! / totalPower);
  }
  const varianceTree = secondTree - reference * reference;
  const variancePower = secondPower - reference * reference;
  const ratio = variancePower / varianceTree;
  let sqrtSum = 0;
  for (let i = 0; i < triangles.length; i++) sqrtSum += Math.sqrt(s2[i]!);
  const varianceOptimal = sqrtSum * sqrtSum - reference * reference;
  console.log(`light tree, 10,000 triangles: ${sampler.tree.nodes.length} nodes built in ${buildMs.toFixed(0)} ms; E = ${reference.toExponential(4)}; variance power-proportional ${variancePower.toExponential(3)}, light tree ${varianceTree.toExponential(3)}, ratio ${ratio.toFixed(1)}; optimal selection (p ~ sqrt(S_i)) ${varianceOptimal.toExponential(3)}`);
  assert.ok(ratio > 10, `variance ratio ${ratio}`);
});
