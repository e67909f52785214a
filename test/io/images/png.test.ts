import { test } from 'node:test';
import assert from 'node:assert/strict';
import { mkdtemp, readFile, rm } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { decode } from 'fast-png';
import { encodePng } from '../../../src/io/images/png.ts';
import { writePng } from '../../../src/io/images/png-node.ts';
import { GpuRendererError } from '../../../src/errors/gpu-renderer-error.ts';

function image(width: number, height: number): { width: number; height: number; data: Uint8ClampedArray } {
  const data = new Uint8ClampedArray(width * height * 4);
  for (let i = 0; i < data.length; i++) data[i] = (i * 37 + (i >> 5)) & 255;
  return { width, height, data };
}

test('encodePng round-trips through fast-png decode', () => {
  const img = image(7, 5);
  const decoded = decode(encodePng(img));
  assert.equal(decoded.width, 7);
  assert.equal(decoded.height, 5);
  assert.equal(decoded.channels, 4);
  assert.equal(decoded.depth, 8);
  assert.deepEqual([...decoded.data], [...img.data]);
});

test('writePng writes a decodable file', async () => {
  const dir = await mkdtemp(join(tmpdir(), 'gpu-renderer-png-'));
  try {
    const img = image(3, 2);
    const path = join(dir, 'out.png');
    await writePng(path, img);
    const decoded = decode(await readFile(path));
    assert.deepEqual([decoded.width, decoded.height], [3, 2]);
    assert.deepEqual([...decoded.data], [...img.data]);
  } finally {
    await rm(dir, { recursive: true, force: true });
  }
});

test('encodePng rejects malformed images with typed errors', () => {
  const isField = (field: string) => (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_OPTION' && e.field === field;
  assert.throws(() => encodePng({ width: 0, height: 1, data: new Uint8ClampedArray(0) }), isField('width'));
  assert.throws(() => encodePng({ width: 2, height: 1.5, data: new Uint8ClampedArray(12) }), isField('height'));
  assert.throws(() => encodePng({ width: 2, height: 2, data: new Uint8ClampedArray(15) }), isField('data'));
});
