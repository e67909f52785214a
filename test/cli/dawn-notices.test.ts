// The CLI's stderr filter for Dawn's adapter-limit notices: exactly those two lines go, in any
// chunking; everything else (errors, other warnings, progress bars rewriting a line) passes intact.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createDawnNoticeFilter } from '../../src/cli/dawn-notices.ts';

const uniform = 'Warning: maxDynamicUniformBuffersPerPipelineLayout artificially reduced from 1000000 to 16 to fit dynamic offset allocation limit.\n';
const storage = 'Warning: maxDynamicStorageBuffersPerPipelineLayout artificially reduced from 500000 to 16 to fit dynamic offset allocation limit.\n';

function filtered(chunks: readonly string[]): { out: string; writes: string[] } {
  const writes: string[] = [];
  const filter = createDawnNoticeFilter((text) => writes.push(text));
  for (const chunk of chunks) filter.push(chunk);
  filter.end();
  return { out: writes.join(''), writes };
}

test('drops the two notices whole, in any chunking, and nothing else', () => {
  const kept = [
    'warning: /images/0: 16-bit PNG reduced to 8 bits per channel\n',
    'Warning: maxDynamicUniformBuffersPerPipelineLayout is something else\n',
    'error [INVALID_GLTF] /meshes/0: broken\n',
    `  ${uniform}`,
    'Warning: maxDynamicUniform',
  ];
  const text = `${uniform}${kept[0]}${storage}${kept[1]}${kept[2]}${kept[3]}${uniform.replace('.\n', '.\r\n')}${kept[4]}`;
  const expected = kept.join('');
  assert.equal(filtered([text]).out, expected);
  // Every split point, and one character at a time.
  for (let at = 0; at <= text.length; at++) assert.equal(filtered([text.slice(0, at), text.slice(at)]).out, expected, `split at ${at}`);
  assert.equal(filtered([...text]).out, expected);
});

test('progress bars rewriting their line pass through at once, not held for a newline', () => {
  const { writes } = filtered(['\rrender: 1/4 spp', '\rrender: 2/4 spp', '\n']);
  assert.deepEqual(writes, ['\rrender: 1/4 spp', '\rrender: 2/4 spp', '\n']);
});
