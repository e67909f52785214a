import { test } from 'node:test';
import assert from 'node:assert/strict';
import { GpuRendererError } from '../../src/errors/gpu-renderer-error.ts';
import { readStruct } from '../../src/gpu-layout/struct-layout.ts';
import { areaLightLayout, packAreaLights, validateAreaLight, type AreaLight } from '../../src/lighting/area-lights.ts';
import { areaLightPdf, intersectAreaLight, sampleAreaLight } from '../../src/lighting/area-light-sampling.ts';
import { initSphericalRectangle, MIN_SPHERICAL_RECTANGLE_SOLID_ANGLE } from '../../src/lighting/spherical-rectangle.ts';
import { add, cross, dot, length, normalize, scale, sub, type Vec3 } from '../../src/lighting/vec3.ts';
import { chiSquareTest, meanAndError, relDiff, rng, uniformSphere } from './helpers.ts';

function expectField(fn: () => unknown, field: string): void {
  assert.throws(fn, (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_LIGHT' && e.field === field);
}

test('area lights: validation names the field', () => {
  const r = validateAreaLight({ type: 'rectangle', center: [0, 2, 0], edgeU: [2, 0, 0], edgeV: [0, 0, 1], emission: [1, 2, 3], intensity: 2 });
  assert.deepEqual(r.normal, [0, -1, 0]);
  assert.equal(r.area, 2);
  assert.deepEqual(r.radiance, [2, 4, 6]);
  assert.equal(r.twoSided, false);
  expectField(() => validateAreaLight({ type: 'triangle' }, 'lights[2]'), 'lights[2].type');
  expectField(() => validateAreaLight({ type: 'rectangle', center: [0, 0, Infinity], edgeU: [1, 0, 0], edgeV: [0, 1, 0] }, 'l'), 'l.center[2]');
  expectField(() => validateAreaLight({ type: 'rectangle', center: [0, 0, 0], edgeU: [0, 0, 0], edgeV: [0, 1, 0] }, 'l'), 'l.edgeU');
  expectField(() => validateAreaLight({ type: 'rectangle', center: [0, 0, 0], edgeU: [1, 0, 0], edgeV: [0.1, 1, 0] }, 'l'), 'l.edgeV');
  expectField(() => validateAreaLight({ type: 'disk', center: [0, 0, 0], normal: [0, 1, 0], radius: -1 }, 'l'), 'l.radius');
  expectField(() => validateAreaLight({ type: 'disk', center: [0, 0, 0], normal: [0, 0, 0], radius: 1 }, 'l'), 'l.normal');
  expectField(() => validateAreaLight({ type: 'sphere', center: [0, 0, 0], radius: Number.NaN }, 'l'), 'l.radius');
  expectField(() => validateAreaLight({ type: 'sphere', center: [0, 0, 0], radius: 1, emission: [1, -2, 0] }, 'l'), 'l.emission[1]');
  expectField(() => validateAreaLight({ type: 'sphere', center: [0, 0, 0], radius: 1, intensity: -3 }, 'l'), 'l.intensity');
  expectField(() => validateAreaLight({ type: 'sphere', center: [0, 0, 0], radius: 1, twoSided: 1 }, 'l'), 'l.twoSided');
});

test('area lights pack into 80-byte AreaLight records', () => {
  assert.equal(areaLightLayout.size, 80);
  const lights = [
    validateAreaLight({ type: 'rectangle', center: [0, 2, 0], edgeU: [2, 0, 0], edgeV: [0, 0, 1], twoSided: true }),
    validateAreaLight({ type: 'sphere', center: [1, 1, 1], radius: 0.5, emission: [3, 3, 3] }),
  ];
  const view = new DataView(packAreaLights(lights));
  const rect = readStruct(areaLightLayout, view, 0);
  assert.deepEqual(rect.corner, [-1, 2, -0.5]);
  assert.equal(rect.kind, 0);
  assert.equal(rect.flags, 1);
  const sphere = readStruct(areaLightLayout, view, 1);
  assert.equal(sphere.kind, 2);
  assert.equal(sphere.radius, 0.5);
  assert.deepEqual(sphere.radiance, [3, 3, 3]);
});

/** Solid angle of triangle (a, b, c) seen from the origin (Van Oosterom and Strackee 1983). */
function triangleSolidAngle(a: Vec3, b: Vec3, c: Vec3): number {
  const la = length(a);
  const lb = length(b);
  const lc = length(c);
  const num = Math.abs(dot(a, cross(b, c)));
  const den = la * lb * lc + dot(a, b) * lc + dot(a, c) * lb + dot(b, c) * la;
  return 2 * Math.atan2(num, den);
}

test('spherical rectangle solid angle equals the two-triangle Van Oosterom-Strackee value', () => {
  const random = rng(21);
  for (let k = 0; k < 500; k++) {
    const n = uniformSphere(random);
    const t = normalize(cross(n, Math.abs(n[0]) > 0.9 ? [0, 1, 0] : [1, 0, 0]));
    const b = cross(n, t);
    const ex = scale(t, 0.1 + 3 * random());
    const ey = scale(b, 0.1 + 3 * random());
    const s: Vec3 = [4 * random() - 2, 4 * random() - 2, 4 * random() - 2];
    const o: Vec3 = [4 * random() - 2, 4 * random() - 2, 4 * random() - 2];
    if (Math.abs(dot(sub(s, o), n)) < 1e-3) continue;
    const q = initSphericalRectangle(s, ex, ey, o);
    const [a, c1, c2, c3] = [sub(s, o), sub(add(s, ex), o), sub(add(add(s, ex), ey), o), sub(add(s, ey), o)];
    const reference = triangleSolidAngle(a, c1, c2) + triangleSolidAngle(a, c2, c3);
    assert.ok(Math.abs(q.solidAngle - reference) < 1e-9 * Math.max(1, reference), `${q.solidAngle} vs ${reference}`);
  }
});

interface Case {
  name: string;
  light: AreaLight;
  p: Vec3;
  /** Maps a sampled point to a cell in [0, cells); `cellOf` and `cellQuadrature` share the grid. */
  cells: number;
  cellOf: (point: Vec3) => number;
  /** Probability of each cell: the integral of pdf_A = pdf_omega |cos| / d^2 over its area. */
  cellProbability: (cell: number) => number;
}

function pdfArea(light: AreaLight, p: Vec3, x: Vec3, normal: Vec3): number {
  const d = sub(x, p);
  const dist = length(d);
  const w = scale(d, 1 / dist);
  return (areaLightPdf(light, p, w) * Math.abs(dot(w, normal))) / (dist * dist);
}

function rectangleCase(name: string, p: Vec3, size: number): Case {
  const light = validateAreaLight({ type: 'rectangle', center: [0.3, 1, -0.2], edgeU: [size, 0, 0], edgeV: [0, 0, 0.6 * size], twoSided: true });
  const corner = sub(sub(light.center, scale(light.edgeU, 0.5)), scale(light.edgeV, 0.5));
  const g = 10;
  const m = 6;
  return {
    name,
    light,
    p,
    cells: g * g,
    cellOf: (x) => {
      const s = dot(sub(x, corner), light.edgeU) / dot(light.edgeU, light.edgeU);
      const t = dot(sub(x, corner), light.edgeV) / dot(light.edgeV, light.edgeV);
      return Math.min(g - 1, Math.floor(s * g)) * g + Math.min(g - 1, Math.floor(t * g));
    },
    cellProbability: (cell) => {
      const i = Math.floor(cell / g);
      const j = cell % g;
      let sum = 0;
      for (let a = 0; a < m; a++) {
        for (let b = 0; b < m; b++) {
          const x = add(add(corner, scale(light.edgeU, (i + (a + 0.5) / m) / g)), scale(light.edgeV, (j + (b + 0.5) / m) / g));
          sum += pdfArea(light, p, x, light.normal);
        }
      }
      return (sum * light.area) / (g * g * m * m);
    },
  };
}

function diskCase(): Case {
  const light = validateAreaLight({ type: 'disk', center: [0, 2, 0], normal: [0.2, -1, 0.1], radius: 0.8 });
  const p: Vec3 = [0.9, 0.3, -0.4];
  const g = 8;
  const m = 6;
  const R = light.radius;
  const polar = (x: Vec3): [number, number] => {
    const r = sub(x, light.center);
    const u = dot(r, light.edgeU);
    const v = dot(r, light.edgeV);
    const phi = Math.atan2(v, u) + Math.PI;
    return [(u * u + v * v) / (R * R), phi / (2 * Math.PI)];
  };
  return {
    name: 'disk',
    light,
    p,
    cells: g * g,
    cellOf: (x) => {
      const [rho, f] = polar(x);
      return Math.min(g - 1, Math.floor(rho * g)) * g + Math.min(g - 1, Math.floor(f * g));
    },
    cellProbability: (cell) => {
      const i = Math.floor(cell / g);
      const j = cell % g;
      let sum = 0;
      for (let a = 0; a < m; a++) {
        for (let b = 0; b < m; b++) {
          const rho = (i + (a + 0.5) / m) / g;
          const phi = 2 * Math.PI * ((j + (b + 0.5) / m) / g) - Math.PI;
          const r = R * Math.sqrt(rho);
          const x = add(light.center, add(scale(light.edgeU, r * Math.cos(phi)), scale(light.edgeV, r * Math.sin(phi))));
          sum += pdfArea(light, p, x, light.normal);
        }
      }
      // dA = (R^2 / 2) d rho d phi over rho in [0, 1], phi in [0, 2 pi).
      return (sum * (R * R / 2) * 2 * Math.PI) / (g * g * m * m);
    },
  };
}

function insideSphereCase(): Case {
  const light = validateAreaLight({ type: 'sphere', center: [0, 0, 0], radius: 1, twoSided: true });
  const p: Vec3 = [0.3, 0.5, -0.2];
  const g = 8;
  const m = 6;
  return {
    name: 'inside a two-sided sphere',
    light,
    p,
    cells: g * g,
    cellOf: (x) => {
      const z = Math.min(1, Math.max(-1, x[2]));
      const phi = Math.atan2(x[1], x[0]) + Math.PI;
      return Math.min(g - 1, Math.floor(((1 - z) / 2) * g)) * g + Math.min(g - 1, Math.floor((phi / (2 * Math.PI)) * g));
    },
    cellProbability: (cell) => {
      const i = Math.floor(cell / g);
      const j = cell % g;
      let sum = 0;
      for (let a = 0; a < m; a++) {
        for (let b = 0; b < m; b++) {
          const z = 1 - 2 * ((i + (a + 0.5) / m) / g);
          const phi = 2 * Math.PI * ((j + (b + 0.5) / m) / g) - Math.PI;
          const r = Math.sqrt(1 - z * z);
          const x: Vec3 = [r * Math.cos(phi), r * Math.sin(phi), z];
          sum += pdfArea(light, p, x, x);
        }
      }
      return (sum * 4 * Math.PI) / (g * g * m * m);
    },
  };
}

test('area light samplers follow their pdfs (chi-square over cells of the light surface)', () => {
  const cases = [
    rectangleCase('rectangle, spherical sampling', [0.1, 0.2, 0.3], 1.5),
    rectangleCase('rectangle, from behind (two-sided)', [0.5, 1.8, 0.1], 1.2),
    rectangleCase('rectangle, area fallback (tiny solid angle)', [0.3, -30, -0.2], 0.3),
    diskCase(),
    insideSphereCase(),
  ];
  for (const c of cases) {
    const n = 100_000;
    const observed = new Float64Array(c.cells);
    const random = rng(7);
    for (let k = 0; k < n; k++) {
      const s = sampleAreaLight(c.light, c.p, random(), random());
      assert.ok(s.pdf > 0, c.name);
      observed[c.cellOf(s.point)]++;
    }
    const expected = new Float64Array(c.cells);
    let total = 0;
    for (let cell = 0; cell < c.cells; cell++) {
      expected[cell] = n * c.cellProbability(cell);
      total += expected[cell]!;
    }
    assert.ok(Math.abs(total / n - 1) < 2e-3, `${c.name}: pdf integrates to ${total / n}`);
    const r = chiSquareTest(observed, expected);
    assert.ok(!r.outsideSupport && r.pValue > 0.001, `${c.name}: chi2 ${r.chi2.toFixed(1)} dof ${r.dof} p ${r.pValue}`);
  }
});

test('sphere cone sampling is uniform in the subtended cone (chi-square), also for tiny cones', () => {
  for (const [dist, radius] of [[3, 1], [5000, 0.7]] as const) {
    const light = validateAreaLight({ type: 'sphere', center: [0, 0, dist], radius });
    const p: Vec3 = [0, 0, 0];
    const oneMinusCosMax = 1 - Math.sqrt(1 - (radius / dist) ** 2);
    const g = 10;
    const observed = new Float64Array(g * g);
    const random = rng(9);
    const n = 100_000;
    for (let k = 0; k < n; k++) {
      const s = sampleAreaLight(light, p, random(), random());
      // The sampled point lies on the sphere and along the returned direction.
      assert.ok(Math.abs(length(sub(s.point, light.center)) - radius) < 1e-9 * dist);
      assert.ok(length(sub(add(p, scale(s.direction, s.distance)), s.point)) < 1e-9 * dist);
      const oneMinusCos = Math.hypot(s.direction[0], s.direction[1], s.direction[2] - 1) ** 2 / 2;
      const phi = Math.atan2(s.direction[1], s.direction[0]) + Math.PI;
      const a = Math.min(g - 1, Math.floor((oneMinusCos / oneMinusCosMax) * g));
      const b = Math.min(g - 1, Math.floor((phi / (2 * Math.PI)) * g));
      observed[a * g + b]++;
      assert.ok(relDiff(s.pdf, 1 / (2 * Math.PI * oneMinusCosMax)) < 1e-6);
    }
    const r = chiSquareTest(observed, new Float64Array(g * g).fill(n / (g * g)));
    assert.ok(r.pValue > 0.001, `sphere at ${dist}: chi2 ${r.chi2} p ${r.pValue}`);
  }
});

test('sampled pdfs equal areaLightPdf of the sampled direction; one-sided lights are dark from behind', () => {
  const lights = [
    validateAreaLight({ type: 'rectangle', center: [0, 2, 0], edgeU: [1, 0, 0], edgeV: [0, 0, 1] }),
    validateAreaLight({ type: 'rectangle', center: [0, 200, 0], edgeU: [1, 0, 0], edgeV: [0, 0, 1] }),
    validateAreaLight({ type: 'disk', center: [0, 2, 0], normal: [0, -1, 0], radius: 0.5 }),
    validateAreaLight({ type: 'sphere', center: [0, 3, 0], radius: 0.5 }),
    validateAreaLight({ type: 'sphere', center: [0, 0.1, 0], radius: 0.5, twoSided: true }),
  ];
  const random = rng(12);
  for (const light of lights) {
    for (let k = 0; k < 2000; k++) {
      const p: Vec3 = [random() - 0.5, random() * 0.5 - 0.2, random() - 0.5];
      const s = sampleAreaLight(light, p, random(), random());
      if (s.pdf === 0) continue;
      assert.ok(relDiff(s.pdf, areaLightPdf(light, p, s.direction)) < 1e-6, `${light.type} pdf ${s.pdf} vs ${areaLightPdf(light, p, s.direction)}`);
      const hit = intersectAreaLight(light, p, s.direction);
      assert.ok(hit !== null && relDiff(hit.distance, s.distance) < 1e-6);
      assert.deepEqual(hit.radiance, s.radiance);
    }
  }
  // From above, the downward-facing one-sided rectangle and disk give nothing.
  for (const light of [lights[0]!, lights[2]!]) {
    assert.equal(sampleAreaLight(light, [0, 3, 0], 0.5, 0.5).pdf, 0);
    assert.equal(areaLightPdf(light, [0, 3, 0], [0, -1, 0]), 0);
  }
  // Inside a one-sided sphere: nothing.
  const sphere = validateAreaLight({ type: 'sphere', center: [0, 0, 0], radius: 1 });
  assert.equal(sampleAreaLight(sphere, [0, 0, 0], 0.3, 0.3).pdf, 0);
  assert.equal(areaLightPdf(sphere, [0, 0, 0], [0, 1, 0]), 0);
});

/** Irradiance from a uniform polygon of radiance 1 above the tangent plane (Lambert's formula). */
function polygonIrradiance(p: Vec3, n: Vec3, vertices: Vec3[]): number {
  let e = 0;
  for (let k = 0; k < vertices.length; k++) {
    const a = normalize(sub(vertices[k]!, p));
    const b = normalize(sub(vertices[(k + 1) % vertices.length]!, p));
    const c = cross(a, b);
    e += Math.acos(Math.min(1, Math.max(-1, dot(a, b)))) * dot(n, normalize(c));
  }
  return Math.abs(e) / 2;
}

test('direct-lighting estimators are unbiased: irradiance from rectangle, disk and sphere lights', () => {
  const n: Vec3 = normalize([0.2, 1, -0.1]);
  const p: Vec3 = [0.1, 0, 0.2];
  const configs: { light: AreaLight; reference: number }[] = [];
  for (const [h, size] of [[1.5, 2], [60, 1]] as const) {
    const light = validateAreaLight({ type: 'rectangle', center: [0.5, h, 0.3], edgeU: [size, 0, 0], edgeV: [0, 0, 0.7 * size] });
    const c = sub(sub(light.center, scale(light.edgeU, 0.5)), scale(light.edgeV, 0.5));
    const verts = [c, add(c, light.edgeU), add(add(c, light.edgeU), light.edgeV), add(c, light.edgeV)];
    configs.push({ light, reference: polygonIrradiance(p, n, verts) });
  }
  assert.ok(initSphericalRectangle(...(() => {
    const l = configs[1]!.light;
    return [sub(sub(l.center, scale(l.edgeU, 0.5)), scale(l.edgeV, 0.5)), l.edgeU, l.edgeV, p] as const;
  })()).solidAngle < MIN_SPHERICAL_RECTANGLE_SOLID_ANGLE, 'the far rectangle exercises the area fallback');
  // Disk on the axis of the normal: E = pi r^2 / (r^2 + h^2).
  const disk = validateAreaLight({ type: 'disk', center: add(p, scale(n, 2)), normal: scale(n, -1), radius: 0.7 });
  configs.push({ light: disk, reference: (Math.PI * 0.49) / (0.49 + 4) });
  // Sphere entirely above the horizon: E = pi (r / d)^2 cos(beta).
  const axis = normalize([0.5, 1, 0.2]);
  const sphere = validateAreaLight({ type: 'sphere', center: add(p, scale(axis, 3)), radius: 0.8 });
  configs.push({ light: sphere, reference: Math.PI * (0.8 / 3) ** 2 * dot(axis, n) });
  const random = rng(31);
  for (const { light, reference } of configs) {
    const values = new Float64Array(50_000);
    for (let k = 0; k < values.length; k++) {
      const s = sampleAreaLight(light, p, random(), random());
      values[k] = s.pdf > 0 ? (s.radiance[0] * Math.max(0, dot(n, s.direction))) / s.pdf : 0;
    }
    const { mean, stderr } = meanAndError(values);
    assert.ok(Math.abs(mean - reference) < 4 * stderr + 1e-12, `${light.type}: ${mean} +- ${stderr} vs ${reference}`);
  }
});
