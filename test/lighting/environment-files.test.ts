import { test } from 'node:test';
import assert from 'node:assert/strict';
import { mkdtempSync, writeFileSync, rmSync } from 'node:fs';
import { createServer } from 'node:http';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { pathToFileURL } from 'node:url';
import { GpuRendererError } from '../../src/errors/gpu-renderer-error.ts';
import { loadEnvironmentMap } from '../../src/lighting/load-environment-map.ts';
import { assertDecodedMatches, encodeExr, encodeHdr, exrSource, sourceImage } from '../io/images/environment-encoders.ts';

test('OpenEXR: truncated or corrupt files raise INVALID_ENVIRONMENT', async () => {
  const good = encodeExr(16, 20, exrSource(16, 20), 'half', 'zip');
  for (const cut of [3, 40, good.length - 10, Math.floor(good.length / 2)]) {
    await assert.rejects(loadEnvironmentMap(good.subarray(0, cut)), (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_ENVIRONMENT');
  }
});

// ---- loadEnvironmentMap --------------------------------------------------------------------------

test('loadEnvironmentMap reads bytes, paths, file URLs and http URLs, and validates the texels', async () => {
  const w = 12;
  const h = 6;
  const rgb = sourceImage(w, h, 9);
  const hdr = encodeHdr(w, h, rgb, { rle: true });
  const fromBytes = await loadEnvironmentMap(hdr, { intensity: 2, rotationRadians: 0.5 });
  assert.equal(fromBytes.intensity, 2);
  assert.equal(fromBytes.rotationRadians, 0.5);
  assertDecodedMatches(fromBytes.data, w, h, rgb, 2 ** -8);
  const exr = encodeExr(w, h, exrSource(w, h), 'float', 'none');
  assert.equal((await loadEnvironmentMap(exr.buffer as ArrayBuffer)).width, w);

  const dir = mkdtempSync(join(tmpdir(), 'env-'));
  try {
    const path = join(dir, 'sky.hdr');
    writeFileSync(path, hdr);
    assert.deepEqual((await loadEnvironmentMap(path)).data, fromBytes.data);
    assert.deepEqual((await loadEnvironmentMap(pathToFileURL(path))).data, fromBytes.data);
    await assert.rejects(loadEnvironmentMap(join(dir, 'missing.hdr')), (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_ENVIRONMENT');
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }

  const server = createServer((req, res) => {
    if (req.url === '/sky.exr') res.end(exr);
    else res.writeHead(404).end();
  });
  await new Promise<void>((resolve) => server.listen(0, '127.0.0.1', resolve));
  try {
    const { port } = server.address() as { port: number };
    const fetched = await loadEnvironmentMap(`http://127.0.0.1:${port}/sky.exr`);
    assert.equal(fetched.width, w);
    await assert.rejects(loadEnvironmentMap(new URL(`http://127.0.0.1:${port}/none.hdr`)), /HTTP 404/);
  } finally {
    server.close();
  }

  // Negative radiance is legal in EXR but not in an environment map: the texel is named.
  const negative = exrSource(w, h);
  negative[3 * 7 + 1] = -1;
  await assert.rejects(loadEnvironmentMap(encodeExr(w, h, negative, 'float', 'none')), (e: unknown) => e instanceof GpuRendererError && e.field === 'source.data[29]');
  await assert.rejects(loadEnvironmentMap(new Uint8Array([1, 2, 3, 4, 5])), /not a Radiance/);
  await assert.rejects(loadEnvironmentMap(42 as unknown as string), (e: unknown) => e instanceof GpuRendererError && e.field === 'source');
});

test("negativeTexels: 'error' refuses a map with a channel below zero (lossy EXR ringing); 'zero' sets it to 0 and reports it", async () => {
  const w = 8;
  const h = 4;
  const rgb = exrSource(w, h);
  // Two negative channels, as DWA compression leaves beside bright texels.
  rgb[3 * 9 + 1] = -0.25;
  rgb[3 * 20 + 2] = -1.5;
  const exr = encodeExr(w, h, rgb, 'float', 'none');
  await assert.rejects(loadEnvironmentMap(exr), (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_ENVIRONMENT' && e.field === 'source.data[37]');
  let report: { channels: number; addedEnergyFraction: number } | undefined;
  const map = await loadEnvironmentMap(exr, { negativeTexels: 'zero', onNegativeTexels: (r) => (report = r) });
  assert.equal(map.data[4 * 9 + 1], 0);
  assert.equal(map.data[4 * 20 + 2], 0);
  let kept = 0;
  for (const v of rgb) if (v >= 0) kept += v;
  assert.equal(report?.channels, 2);
  assert.ok(Math.abs(report!.addedEnergyFraction - 1.75 / kept) < 1e-6 * (1.75 / kept), `added ${report!.addedEnergyFraction} vs ${1.75 / kept}`);
  // Every other channel is decoded as it is.
  for (let t = 0; t < w * h; t++) for (let c = 0; c < 3; c++) if (rgb[3 * t + c]! >= 0) assert.ok(Math.abs(map.data[4 * t + c]! - rgb[3 * t + c]!) <= 2 ** -23 * Math.abs(rgb[3 * t + c]!));
  await assert.rejects(loadEnvironmentMap(exr, { negativeTexels: 'clamp' as never }), (e: unknown) => e instanceof GpuRendererError && e.field === 'negativeTexels');
});
