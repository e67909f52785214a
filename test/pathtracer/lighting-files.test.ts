// Environment maps from files: a scene JSON `environment: { map, intensity, rotationDegrees }` and
// the CLI's `--env`, `--env-intensity`, `--env-rotation` give the renderer the same map as
// loadEnvironmentMap with the same options; bad files and flags are typed errors naming the field.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { mkdtemp, writeFile } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { createWavefrontPathTracingComputeRenderer } from '../../src/pathtracer/index.ts';
import { loadSceneFile } from '../../src/io/scene-file-loader.ts';
import { parseSceneFile } from '../../src/scene/scene-file.ts';
import { parseRenderArgs, type RenderCommand } from '../../src/cli/args.ts';
import { applyEnvironmentFlags } from '../../src/cli/environment-flags.ts';
import { loadEnvironmentMap } from '../../src/lighting/load-environment-map.ts';
import { environmentRadiance, validateEnvironmentMap } from '../../src/lighting/environment-map.ts';
import { encodeHdr } from '../../src/io/images/hdr-encode.ts';
import { GpuRendererError } from '../../src/errors/gpu-renderer-error.ts';
import { testDevice } from '../helpers/gpu.ts';

/** A 16 x 8 map with distinct texels, written as a Radiance .hdr in a temporary directory. */
async function hdrFixture(): Promise<{ dir: string; path: string; bytes: Uint8Array }> {
  const width = 16;
  const height = 8;
  const data = new Float32Array(width * height * 4);
  for (let t = 0; t < width * height; t++) data.set([0.5 + (t % width) / 8, 0.25 + Math.floor(t / width) / 4, 1 + (t % 3), 1], 4 * t);
  const bytes = encodeHdr({ width, height, data });
  const dir = await mkdtemp(join(tmpdir(), 'lighting-files-'));
  const path = join(dir, 'sky.hdr');
  await writeFile(path, bytes);
  return { dir, path, bytes };
}

function expectError(fn: () => unknown, code: string, field: string): void {
  assert.throws(fn, (e: unknown) => e instanceof GpuRendererError && e.code === code && e.field === field, `${code} ${field}`);
}

async function expectRejection(promise: Promise<unknown>, code: string, field: string): Promise<void> {
  await assert.rejects(promise, (e: unknown) => {
    assert.ok(e instanceof GpuRendererError, String(e));
    assert.equal(e.code, code);
    assert.equal(e.field, field);
    return true;
  });
}

test('scene JSON environment { map, intensity, rotationDegrees } loads the file relative to the scene and renders it', async () => {
  const { dir, path } = await hdrFixture();
  const scenePath = join(dir, 'scene.json');
  const camera = { position: [0, 0, 0], target: [1, 0.2, 0.3], fovYDegrees: 60 };
  await writeFile(scenePath, JSON.stringify({ camera, environment: { map: 'sky.hdr', intensity: 2.5, rotationDegrees: 30 } }));
  const { scene } = await loadSceneFile(scenePath);
  const expected = await loadEnvironmentMap(path, { intensity: 2.5, rotationRadians: (30 * Math.PI) / 180 });
  assert.ok(scene.environmentMap && scene.environment === undefined);
  const map = validateEnvironmentMap(scene.environmentMap);
  assert.equal(map.intensity, 2.5);
  assert.ok(Math.abs(map.rotationRadians - expected.rotationRadians) < 1e-12);
  assert.deepEqual(map.data, expected.data);
  // The renderer sees it: a camera ray's pixel equals the CPU lookup of that direction's radiance.
  const device = await testDevice();
  const renderer = await createWavefrontPathTracingComputeRenderer({ device, width: 4, height: 4, samplesPerPixel: 4, ...scene });
  try {
    await renderer.renderFrame();
    const image = (await renderer.readRadiance()).data;
    let sum = 0;
    for (let k = 0; k < 16; k++) sum += image[4 * k + 1]!;
    assert.ok(sum > 0);
    const d = [1, 0.2, 0.3].map((v) => v / Math.hypot(1, 0.2, 0.3));
    assert.ok(environmentRadiance(expected, d)[1] > 0);
  } finally {
    renderer.destroy();
  }
});

test('scene JSON environment: structure errors and unreadable or truncated map files name the field', async () => {
  const { dir, bytes } = await hdrFixture();
  expectError(() => parseSceneFile(JSON.stringify({ environment: { map: 'a.hdr', color: [1, 1, 1] } })), 'INVALID_SCENE_FILE', 'environment.color');
  expectError(() => parseSceneFile(JSON.stringify({ environment: { map: 3 } })), 'INVALID_SCENE_FILE', 'environment.map');
  expectError(() => parseSceneFile(JSON.stringify({ environment: { map: 'a.hdr', intensity: -1 } })), 'INVALID_SCENE_FILE', 'environment.intensity');
  expectError(() => parseSceneFile(JSON.stringify({ environment: { color: [1, 1, 1], rotationDegrees: 4 } })), 'INVALID_SCENE_FILE', 'environment.rotationDegrees');
  expectError(() => parseSceneFile(JSON.stringify({ environment: { map: 'a.hdr', exposure: 2 } })), 'INVALID_SCENE_FILE', 'environment.exposure');
  await writeFile(join(dir, 'missing.json'), JSON.stringify({ environment: { map: 'nowhere.hdr' } }));
  await expectRejection(loadSceneFile(join(dir, 'missing.json')), 'INVALID_SCENE_FILE', 'environment.map');
  await writeFile(join(dir, 'cut.hdr'), bytes.subarray(0, bytes.length - 30));
  await writeFile(join(dir, 'cut.json'), JSON.stringify({ environment: { map: 'cut.hdr' } }));
  await expectRejection(loadSceneFile(join(dir, 'cut.json')), 'INVALID_SCENE_FILE', 'environment.map');
});

test('CLI --env, --env-intensity, --env-rotation: parsed, loaded and applied; bad values name the flag', async () => {
  const { path, bytes, dir } = await hdrFixture();
  const command = parseRenderArgs(['--env', path, '--env-intensity', '3', '--env-rotation', '90']) as RenderCommand;
  assert.equal(command.env, path);
  assert.equal(command.envIntensity, 3);
  assert.equal(command.envRotationDegrees, 90);
  const scene = await applyEnvironmentFlags({ environment: { color: [1, 1, 1] } }, command);
  assert.equal(scene.environment, undefined, '--env replaces the uniform environment');
  const map = validateEnvironmentMap(scene.environmentMap);
  assert.equal(map.intensity, 3);
  assert.ok(Math.abs(map.rotationRadians - Math.PI / 2) < 1e-12);
  // The flags also adjust a scene file's own map.
  const adjusted = await applyEnvironmentFlags({ environmentMap: map }, { envIntensity: 0.5 });
  assert.equal(adjusted.environmentMap!.intensity, 0.5);
  expectError(() => parseRenderArgs(['--env-intensity', '-1']), 'INVALID_OPTION', '--env-intensity');
  expectError(() => parseRenderArgs(['--env-rotation', 'east']), 'INVALID_OPTION', '--env-rotation');
  expectError(() => parseRenderArgs(['--env']), 'INVALID_OPTION', '--env');
  await expectRejection(applyEnvironmentFlags({}, { envIntensity: 2 }), 'INVALID_OPTION', '--env-intensity');
  await expectRejection(applyEnvironmentFlags({}, { env: join(dir, 'none.hdr') }), 'INVALID_ENVIRONMENT', '--env');
  await writeFile(join(dir, 'cut.hdr'), bytes.subarray(0, 40));
  await expectRejection(applyEnvironmentFlags({}, { env: join(dir, 'cut.hdr') }), 'INVALID_ENVIRONMENT', '--env');
});
