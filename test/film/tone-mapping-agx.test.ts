import { test } from 'node:test';
import assert from 'node:assert/strict';
import {
  agxContrastApprox,
  applyToneMapping,
  encodeRadianceToRgba8,
  exposureMultiplier,
  isToneMapping,
  toneMapAgx,
} from '../../src/film/tone-mapping.ts';
import { GpuRendererError } from '../../src/errors/gpu-renderer-error.ts';
import { rng } from '../helpers/random.ts';

type M3 = number[][];
const mulV = (m: M3, v: number[]): number[] => m.map((r) => r[0] * v[0] + r[1] * v[1] + r[2] * v[2]);
const mulM = (a: M3, b: M3): M3 => a.map((r) => [0, 1, 2].map((j) => r[0] * b[0][j] + r[1] * b[1][j] + r[2] * b[2][j]));
function inverse(m: M3): M3 {
  const [[a, b, c], [d, e, f], [g, h, i]] = m;
  const A = e * i - f * h;
  const B = f * g - d * i;
  const C = d * h - e * g;
  const det = a * A + b * B + c * C;
  return [
    [A / det, (c * h - b * i) / det, (b * f - c * e) / det],
    [B / det, (a * i - c * g) / det, (c * d - a * f) / det],
    [C / det, (b * g - a * h) / det, (a * e - b * d) / det],
  ];
}
/** RGB -> XYZ from chromaticities (SMPTE RP 177 normalised primary matrix). */
function rgbToXyz(primaries: number[][], white: number[]): M3 {
  const xyz = ([x, y]: number[]) => [x / y, 1, (1 - x - y) / y];
  const p = [0, 1, 2].map((row) => primaries.map((pr) => xyz(pr)[row]));
  const s = mulV(inverse(p), xyz(white));
  return p.map((row) => row.map((v, j) => v * s[j]));
}

// Independent evaluation of the published AgX recipe. Constants are the published ones:
// ITU-R BT.709 / BT.2020 primaries with the D65 white; the inset matrix and Filament's
// AgXOutsetMatrixInv (google/filament PR 7236) written as rows; LOG2_MIN -10, LOG2_MAX +6.5 around
// middle grey 0.18; the iolite polynomial coefficients.
const d65 = [0.3127, 0.329];
const xyzFrom709 = rgbToXyz([[0.64, 0.33], [0.3, 0.6], [0.15, 0.06]], d65);
const xyzFrom2020 = rgbToXyz([[0.708, 0.292], [0.17, 0.797], [0.131, 0.046]], d65);
const to2020 = mulM(inverse(xyzFrom2020), xyzFrom709);
const to709 = inverse(to2020);
const inset: M3 = [
  [0.856627153315983, 0.0951212405381588, 0.0482516061458583],
  [0.137318972929847, 0.761241990602591, 0.101439036467562],
  [0.11189821299995, 0.0767994186031903, 0.811302368396859],
];
const outsetInverse: M3 = [
  [0.899796955911611, 0.0871996192028351, 0.013003424885555],
  [0.11142098895748, 0.875575586156966, 0.0130034248855548],
  [0.11142098895748, 0.0871996192028349, 0.801379391839686],
];
const outset = inverse(outsetInverse);
const minEv = Math.log2(Math.pow(2, -10) * 0.18);
const maxEv = Math.log2(Math.pow(2, 6.5) * 0.18);
const poly = (x: number): number =>
  15.5 * x ** 6 - 40.14 * x ** 5 + 31.96 * x ** 4 - 6.868 * x ** 3 + 0.4298 * x ** 2 + 0.1191 * x - 0.00232;
const clamp01 = (v: number): number => Math.min(1, Math.max(0, v));

function referenceAgx(rgb: number[], m709to2020 = to2020, m2020to709 = to709, evRange = [minEv, maxEv]): number[] {
  const v = mulV(inset, mulV(m709to2020, rgb));
  const s = v.map((c) => poly(clamp01((Math.log2(Math.max(c, 1e-10)) - evRange[0]) / (evRange[1] - evRange[0]))));
  const lin = mulV(outset, s).map((c) => Math.max(c, 0) ** 2.2);
  return mulV(m2020to709, lin).map(clamp01);
}

function colours(): number[][] {
  const out: number[][] = [];
  for (let i = 0; i <= 80; i++) {
    const g = Math.pow(10, -5 + i / 10);
    out.push([g, g, g]);
  }
  const rand = rng(7);
  for (let i = 0; i < 2000; i++) out.push([0, 1, 2].map(() => (rand() < 0.1 ? 0 : Math.pow(10, -4 + 7 * rand()))));
  out.push([100, 0, 0], [0, 100, 0], [0, 0, 100], [1, 0, 0], [0, 0, 0]);
  return out;
}

test('AgX equals an independent evaluation of the published recipe (derived Rec.2020 matrices, inverted outset)', () => {
  let worst = 0;
  for (const c of colours()) {
    const got = toneMapAgx(c);
    const want = referenceAgx(c);
    for (let k = 0; k < 3; k++) worst = Math.max(worst, Math.abs(got[k] - want[k]));
  }
  assert.ok(worst < 1e-12, `max abs difference ${worst}`);
});

test('AgX stays within 5e-4 of three.js r187 constants (4-decimal BT.2407 matrices, rounded EV range)', () => {
  // three.js writes the Rec.709 <-> Rec.2020 matrices rounded to 4 decimals and the EV range as
  // -12.47393 / 4.026069; we use full precision. The difference must stay far below an 8-bit step.
  const threeTo2020: M3 = [
    [0.6274, 0.3293, 0.0433],
    [0.0691, 0.9195, 0.0113],
    [0.0164, 0.088, 0.8956],
  ];
  const threeTo709: M3 = [
    [1.6605, -0.5876, -0.0728],
    [-0.1246, 1.1329, -0.0083],
    [-0.0182, -0.1006, 1.1187],
  ];
  let worst = 0;
  for (const c of colours()) {
    const got = toneMapAgx(c);
    const three = referenceAgx(c, threeTo2020, threeTo709, [-12.47393, 4.026069]);
    for (let k = 0; k < 3; k++) worst = Math.max(worst, Math.abs(got[k] - three[k]));
  }
  assert.ok(worst < 5e-4, `max abs difference ${worst}`);
});

test('AgX on greys: stays grey and equals poly(log-encoded grey)^2.2; middle grey lands at poly(10 / 16.5)^2.2', () => {
  let prev = -1;
  for (let i = 0; i <= 400; i++) {
    const g = Math.pow(10, -5 + i / 40);
    const [r, gg, b] = toneMapAgx([g, g, g]);
    assert.ok(Math.abs(r - gg) < 1e-12 && Math.abs(gg - b) < 1e-12, `grey ${g} -> ${r}, ${gg}, ${b}`);
    const x = clamp01((Math.log2(g) - minEv) / 16.5);
    assert.ok(Math.abs(r - clamp01(Math.max(poly(x), 0) ** 2.2)) < 1e-12);
    assert.ok(r >= prev, `not monotonic at ${g}`);
    prev = r;
  }
  // log2(0.18) sits 10 stops above the minimum of a 16.5-stop range.
  const mid = toneMapAgx([0.18, 0.18, 0.18])[0];
  assert.ok(Math.abs(mid - poly(10 / 16.5) ** 2.2) < 1e-12);
  assert.ok(mid > 0.15 && mid < 0.25, `middle grey -> ${mid}`);
  assert.deepEqual(toneMapAgx([0, 0, 0]), [0, 0, 0]);
  // Above the 16.5-stop range everything is the sigmoid's top, sum of the coefficients 0.99858,
  // so the brightest AgX grey is 0.99858^2.2 (just under display white), as with three.js.
  const top = toneMapAgx([1e6, 1e6, 1e6]);
  for (const v of top) assert.ok(Math.abs(v - 0.99858 ** 2.2) < 1e-12, `${top}`);
  assert.ok(Math.abs(agxContrastApprox(0) + 0.00232) < 1e-15);
  assert.ok(Math.abs(agxContrastApprox(1) - 0.99858) < 1e-12);
});

test('AgX desaturates very bright saturated colours towards white (the "path to white")', () => {
  const dim = toneMapAgx([0.05, 0, 0]);
  const bright = toneMapAgx([500, 0, 0]);
  assert.ok(bright[1] > 0.5 && bright[2] > 0.5, `${bright}`);
  assert.ok(bright[1] / bright[0] > dim[1] / Math.max(dim[0], 1e-9));
  assert.equal(isToneMapping('agx'), true);
  assert.deepEqual(applyToneMapping([0.3, 0.2, 0.1], 'agx'), toneMapAgx([0.3, 0.2, 0.1]));
});

test('exposureEv multiplies by 2^EV alongside the linear exposure', () => {
  assert.equal(exposureMultiplier({}), 1);
  assert.equal(exposureMultiplier({ exposureEv: 1 }), 2);
  assert.equal(exposureMultiplier({ exposureEv: -2, exposure: 3 }), 0.75);
  const radiance = new Float32Array([0.02, 0.2, 1.5, 1, 0.7, 0.01, 0.3, 1]);
  for (const toneMapping of ['agx', 'neutral', 'aces', 'linear'] as const) {
    assert.deepEqual(
      [...encodeRadianceToRgba8(radiance, { toneMapping, exposureEv: 1.5 })],
      [...encodeRadianceToRgba8(radiance, { toneMapping, exposure: 2 ** 1.5 })],
    );
    assert.deepEqual(
      [...encodeRadianceToRgba8(radiance, { toneMapping, exposure: 4, exposureEv: -2 })],
      [...encodeRadianceToRgba8(radiance, { toneMapping })],
    );
  }
  const isField = (field: string) => (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_OPTION' && e.field === field;
  assert.throws(() => exposureMultiplier({ exposureEv: Number.NaN }), isField('exposureEv'));
  assert.throws(() => encodeRadianceToRgba8(radiance, { exposureEv: Infinity }), isField('exposureEv'));
  assert.throws(() => encodeRadianceToRgba8(radiance, { exposure: -1 }), isField('exposure'));
});
