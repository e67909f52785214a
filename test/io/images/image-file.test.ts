import { test } from 'node:test';
import assert from 'node:assert/strict';
import { mkdtemp, readFile, rm } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { decode } from 'fast-png';
import { encodeImageFile, imageFileFormatFromPath, writeImageFile } from '../../../src/io/images/image-file.ts';
import { encodeRadianceToRgba8 } from '../../../src/film/tone-mapping.ts';
import { GpuRendererError } from '../../../src/errors/gpu-renderer-error.ts';
import { readExrWithThree, readHdrWithThree } from './independent-readers.ts';

const width = 10;
const height = 4;
const data = new Float32Array(width * height * 4).map((_, i) => (i % 4 === 3 ? 1 : ((i * 7) % 13) * 0.3));
const image = { width, height, data };

test('writeImageFile picks the format from the extension and writes files independent decoders read', async () => {
  const dir = await mkdtemp(join(tmpdir(), 'gpu-renderer-files-'));
  try {
    const png = await writeImageFile(join(dir, 'a.PNG'), image, { toneMapping: 'agx', exposureEv: 1 });
    assert.equal(png.format, 'png');
    const decodedPng = decode(await readFile(join(dir, 'a.PNG')));
    assert.deepEqual([...decodedPng.data], [...encodeRadianceToRgba8(data, { toneMapping: 'agx', exposure: 2 })]);

    const exr = await writeImageFile(join(dir, 'b.exr'), image, { aovs: { depth: new Float32Array(width * height).fill(2) } });
    assert.equal(exr.format, 'exr');
    const decodedExr = readExrWithThree(new Uint8Array(await readFile(join(dir, 'b.exr'))));
    // EXR is scene-referred: radiance exactly as given (float32 default), not tone mapped.
    assert.deepEqual([...decodedExr.data], [...data]);
    assert.deepEqual((decodedExr.header.channels as { name: string }[]).map((c) => c.name), ['A', 'B', 'G', 'R', 'depth.Z']);

    const hdr = await writeImageFile(join(dir, 'c.hdr'), image);
    const decodedHdr = readHdrWithThree(new Uint8Array(await readFile(join(dir, 'c.hdr'))));
    assert.equal(hdr.bytes, (await readFile(join(dir, 'c.hdr'))).length);
    for (let i = 0; i < data.length; i++) if (i % 4 !== 3) assert.ok(Math.abs(decodedHdr.data[i] - data[i]) <= 3.6 / 128 + data[i] / 255);

    // An explicit format wins over the extension.
    const forced = await writeImageFile(join(dir, 'd.bin'), image, { format: 'exr' });
    assert.equal(forced.format, 'exr');
    assert.equal(readExrWithThree(new Uint8Array(await readFile(join(dir, 'd.bin')))).width, width);
  } finally {
    await rm(dir, { recursive: true, force: true });
  }
});

test('format errors are typed: unknown extensions, AOVs in PNG or HDR, unknown formats', async () => {
  const isField = (field: string) => (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_OPTION' && e.field === field;
  assert.equal(imageFileFormatFromPath('/x/y.Hdr'), 'hdr');
  assert.throws(() => imageFileFormatFromPath('out.tiff'), isField('path'));
  assert.throws(() => imageFileFormatFromPath('out'), isField('path'));
  await assert.rejects(writeImageFile('out.jpg', image), isField('path'));
  assert.throws(() => encodeImageFile(image, 'png', { aovs: { albedo: new Float32Array(width * height * 3) } }), isField('aovs'));
  assert.throws(() => encodeImageFile(image, 'hdr', { layers: [{ name: 'x', channels: ['Y'], data: new Float32Array(width * height) }] }), isField('layers'));
  assert.throws(() => encodeImageFile(image, 'tga' as never), isField('format'));
});
