import { test } from 'node:test';
import assert from 'node:assert/strict';
import { compactWgsl } from '../../scripts/shader-build/compact-wgsl.ts';

test('compactWgsl drops line comments, nested block comments, indentation and empty lines, and nothing else', () => {
  const source = [
    '// a header',
    'fn f(x: f32) -> f32 { // trailing',
    '  /* outer /* nested */ still outer',
    '     */ let y = x * 2.0; /**/',
    '',
    '  return y/2.0; // division is not a comment',
    '}',
  ].join('\n');
  assert.equal(compactWgsl(source), ['fn f(x: f32) -> f32 {', 'let y = x * 2.0;', 'return y/2.0;', '}'].join('\n'));
  assert.equal(compactWgsl('a /* unterminated'), 'a');
});
