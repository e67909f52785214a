import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createMediumStack, mediumStackLimit } from '../../src/transport/medium-stack.ts';
import { GpuRendererError } from '../../src/errors/gpu-renderer-error.ts';

test('enter pushes, exit of the innermost pops, and stacks are immutable', () => {
  const empty = createMediumStack();
  assert.equal(empty.current, 0);
  const a = empty.enter(3);
  assert.deepEqual(a.stack.media, [3]);
  const b = a.stack.enter(8);
  assert.deepEqual(b.stack.media, [3, 8]);
  assert.equal(b.stack.current, 8);
  assert.deepEqual(a.stack.media, [3], 'earlier stack is unchanged');
  assert.ok(Object.isFrozen(b.stack.media));
  const c = b.stack.exit(8);
  assert.deepEqual(c.stack.media, [3]);
  assert.equal(c.mismatch, false);
  assert.equal(c.overflow, false);
});

test('entering past four media reports overflow and keeps the stack', () => {
  assert.equal(mediumStackLimit, 4);
  let stack = createMediumStack();
  for (const id of [1, 2, 3, 4]) {
    const t = stack.enter(id);
    assert.equal(t.overflow, false);
    stack = t.stack;
  }
  const over = stack.enter(5);
  assert.equal(over.overflow, true);
  assert.equal(over.stack, stack);
  assert.deepEqual(over.stack.media, [1, 2, 3, 4]);
});

test('exiting a medium that is not innermost reports a mismatch', () => {
  const stack = createMediumStack([1, 2, 3]);
  const middle = stack.exit(2);
  assert.equal(middle.mismatch, true);
  assert.deepEqual(middle.stack.media, [1, 3], 'the exited medium is removed');
  const absent = stack.exit(9);
  assert.equal(absent.mismatch, true);
  assert.equal(absent.stack, stack);
});

test('bad ids and too many media throw typed errors', () => {
  const isField = (field: string) => (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_OPTION' && e.field === field;
  assert.throws(() => createMediumStack([1, 2, 3, 4, 5]), isField('ids'));
  assert.throws(() => createMediumStack([1, 0]), isField('ids[1]'));
  assert.throws(() => createMediumStack([1.5]), isField('ids[0]'));
  assert.throws(() => createMediumStack().enter(-1), isField('mediumId'));
});
