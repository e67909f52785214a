import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createMediumStack } from '../../src/transport/medium-stack.ts';
import { dielectricInterface } from '../../src/transport/fresnel.ts';
import { createTransportBranches } from '../../src/transport/transport-branches.ts';
import { GpuRendererError } from '../../src/errors/gpu-renderer-error.ts';

const close = (a: number, b: number, tol: number, message?: string): void => assert.ok(Math.abs(a - b) <= tol, `${message ?? ''} ${a} vs ${b}`);

test('normal incidence reflectance is ((eta - 1) / (eta + 1))^2 from both sides', () => {
  for (const eta of [1.0, 1.33, 1.5, 2.4]) {
    const expected = ((eta - 1) / (eta + 1)) ** 2;
    close(dielectricInterface(1, eta).reflectance, expected, 1e-12, `entering eta=${eta}`);
    close(dielectricInterface(1, 1 / eta).reflectance, expected, 1e-12, `leaving eta=${eta}`);
  }
});

test('at Brewster angle the parallel term vanishes: F = Rs / 2 with Rs = ((eta^2 - 1)/(eta^2 + 1))^2', () => {
  const eta = 1.5;
  const thetaB = Math.atan(eta);
  const rs = ((eta * eta - 1) / (eta * eta + 1)) ** 2;
  close(dielectricInterface(Math.cos(thetaB), eta).reflectance, rs / 2, 1e-12);
});

test('total internal reflection starts at the critical angle asin(1 / ior)', () => {
  const ior = 1.5;
  const critical = Math.asin(1 / ior);
  const inside = createMediumStack([7]);
  for (const theta of [critical, critical + 1e-3, critical + 0.3, Math.PI / 2 - 1e-6]) {
    const b = createTransportBranches({ mediumStack: inside, mediumId: 7, transmission: 1, ior, cosTheta: Math.cos(theta) });
    assert.equal(b.entering, false);
    assert.equal(b.totalInternalReflection, true, `theta=${theta}`);
    assert.equal(b.reflected.weight, 1);
    assert.equal(b.transmitted, null);
    assert.equal(b.branches.length, 1);
  }
  // Just below the critical angle light still escapes, but reflectance is already close to 1.
  const below = createTransportBranches({ mediumStack: inside, mediumId: 7, transmission: 1, ior, cosTheta: Math.cos(critical - 1e-4) });
  assert.equal(below.totalInternalReflection, false);
  assert.ok(below.fresnel > 0.9 && below.fresnel < 1, `F=${below.fresnel}`);
  // Entering from outside never reflects totally.
  const outside = createTransportBranches({ mediumStack: createMediumStack(), mediumId: 7, transmission: 1, ior, cosTheta: Math.cos(critical + 0.3) });
  assert.equal(outside.totalInternalReflection, false);
});

test('lossless interface: reflected + transmitted weights sum to 1 at every angle; base takes the rest otherwise', () => {
  const stack = createMediumStack([2]);
  for (let i = 0; i <= 50; i++) {
    const cosTheta = i / 50;
    for (const [mediumStack, ior] of [[stack, 1.5], [createMediumStack([2, 9]), 1.33]] as const) {
      const b = createTransportBranches({ mediumStack, mediumId: 9, transmission: 1, ior, cosTheta });
      const sum = b.reflected.weight + (b.transmitted?.weight ?? 0);
      close(sum, 1, 1e-12, `cos=${cosTheta}`);
      assert.equal(b.baseWeight, 0);
    }
    const partial = createTransportBranches({ mediumStack: stack, mediumId: 9, transmission: 0.25, ior: 1.5, cosTheta });
    const F = dielectricInterface(cosTheta, 1.5).reflectance;
    close(partial.reflected.weight, F, 1e-15);
    close(partial.transmitted?.weight ?? 0, 0.25 * (1 - F), 1e-15);
    close(partial.reflected.weight + (partial.transmitted?.weight ?? 0) + partial.baseWeight, 1, 1e-12);
  }
});

test('transmitted branch enters or leaves the medium; reflected branch keeps the stack', () => {
  const outside = createMediumStack([1]);
  const enter = createTransportBranches({ mediumStack: outside, mediumId: 4, transmission: 1, ior: 1.5 });
  assert.equal(enter.entering, true);
  assert.equal(enter.eta, 1.5);
  assert.deepEqual(enter.transmitted?.mediumStack.media, [1, 4]);
  assert.equal(enter.transmitted?.mediumId, 4);
  assert.equal(enter.reflected.mediumStack, outside);
  assert.equal(enter.reflected.mediumId, 1);
  // Snell: sin(theta_t) = sin(theta_i) / eta.
  const cosI = Math.cos(0.6);
  const refr = createTransportBranches({ mediumStack: outside, mediumId: 4, transmission: 1, ior: 1.5, cosTheta: cosI });
  close(Math.sqrt(1 - refr.transmitted!.cosTheta ** 2), Math.sin(0.6) / 1.5, 1e-12);

  const inside = createMediumStack([1, 4]);
  const leave = createTransportBranches({ mediumStack: inside, mediumId: 4, transmission: 1, ior: 1.5 });
  assert.equal(leave.entering, false);
  close(leave.eta, 1 / 1.5, 1e-15);
  assert.deepEqual(leave.transmitted?.mediumStack.media, [1]);
  assert.equal(leave.transmitted?.mismatch, false);

  const full = createMediumStack([1, 2, 3, 4]);
  const overflow = createTransportBranches({ mediumStack: full, mediumId: 5, transmission: 1, ior: 1.5 });
  assert.equal(overflow.transmitted?.overflow, true);
  assert.deepEqual(overflow.transmitted?.mediumStack.media, [1, 2, 3, 4]);
});

test('invalid branch options throw typed errors naming the field', () => {
  const stack = createMediumStack();
  const cases: [Record<string, unknown>, string][] = [
    [{ mediumStack: [1], mediumId: 1, transmission: 1, ior: 1.5 }, 'mediumStack'],
    [{ mediumStack: stack, mediumId: 0, transmission: 1, ior: 1.5 }, 'mediumId'],
    [{ mediumStack: stack, mediumId: 1, transmission: 1.5, ior: 1.5 }, 'transmission'],
    [{ mediumStack: stack, mediumId: 1, transmission: 1, ior: 0.5 }, 'ior'],
    [{ mediumStack: stack, mediumId: 1, transmission: 1, ior: 1.5, cosTheta: -0.1 }, 'cosTheta'],
  ];
  for (const [options, field] of cases) {
    assert.throws(
      () => createTransportBranches(options as never),
      (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_OPTION' && e.field === field,
      field,
    );
  }
});
