// Lossy EXRs with negative texels (the HDRIs of @pmndrs/assets, DWAB-compressed): the CLI zeroes
// them by default and says how many and how much energy that adds; --negative-texels error and a
// scene file's environment.negativeTexels choose per use. Decoding through three's EXRLoader (CPU).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { mkdtemp, readFile, writeFile } from 'node:fs/promises';
import { createRequire } from 'node:module';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { parseRenderArgs, type RenderCommand } from '../../src/cli/args.ts';
import { applyEnvironmentFlags } from '../../src/cli/environment-flags.ts';
import { GpuRendererError } from '../../src/errors/gpu-renderer-error.ts';
import { loadSceneFile } from '../../src/io/scene-file-loader.ts';
import { loadEnvironmentMap, type NegativeTexelReport } from '../../src/lighting/load-environment-map.ts';
import { parseSceneFile } from '../../src/scene/scene-file.ts';

const studio = createRequire(import.meta.url).resolve('@pmndrs/assets/hdri/studio.exr.js');

/** The EXR inside the module (`export default 'data:...;base64,...'`). */
async function studioExr(): Promise<Uint8Array> {
  const text = await readFile(studio, 'utf8');
  return new Uint8Array(Buffer.from(text.slice(text.indexOf('base64,') + 7, text.lastIndexOf("'")), 'base64'));
}

async function rejectsWith(promise: Promise<unknown>, code: string, field: string, message?: RegExp): Promise<void> {
  await assert.rejects(promise, (e: unknown) => {
    assert.ok(e instanceof GpuRendererError, String(e));
    assert.equal(e.code, code, e.message);
    assert.ok(e.field === field || e.field?.startsWith(`${field}.`), `field ${e.field}, expected ${field}`);
    if (message) assert.match(e.message, message);
    return true;
  });
}

test('--env takes an @pmndrs/assets .exr.js module; negative texels are zeroed by default and reported', async () => {
  let reference: NegativeTexelReport | undefined;
  const expected = await loadEnvironmentMap(await studioExr(), { negativeTexels: 'zero', onNegativeTexels: (r) => (reference = r) });
  assert.ok(reference!.channels > 0, 'the fixture has negative texels');
  const notes: string[] = [];
  const scene = await applyEnvironmentFlags({}, parseRenderArgs(['--env', studio]) as RenderCommand, (text) => notes.push(text));
  const map = scene.environmentMap!;
  assert.deepEqual([map.width, map.height], [expected.width, expected.height]);
  assert.deepEqual(map.data, expected.data);
  assert.ok(Array.from(map.data as Float32Array).every((v) => v >= 0));
  assert.equal(notes.length, 1);
  assert.match(notes[0]!, new RegExp(`^--env: ${reference!.channels} negative channel values \\(lossy EXR ringing\\) set to 0, adding [0-9.e-]+ % to the map's energy`));
});

test('--negative-texels error refuses the map naming --env; a .js file that is no data: URL module is refused', async () => {
  await rejectsWith(applyEnvironmentFlags({}, parseRenderArgs(['--env', studio, '--negative-texels', 'error']) as RenderCommand), 'INVALID_ENVIRONMENT', '--env', /must be finite and >= 0/);
  const dir = await mkdtemp(join(tmpdir(), 'negative-texels-'));
  await writeFile(join(dir, 'code.js'), "export default fetch('x');\n");
  await rejectsWith(applyEnvironmentFlags({}, { env: join(dir, 'code.js') }), 'INVALID_ENVIRONMENT', '--env', /export default "data:/);
});

test('scene files: environment.negativeTexels, else the loader option (the CLI passes its flag); reports name the field', async () => {
  const dir = await mkdtemp(join(tmpdir(), 'negative-texels-'));
  await writeFile(join(dir, 'studio.exr'), await studioExr());
  const write = async (name: string, environment: object): Promise<string> => {
    const path = join(dir, name);
    await writeFile(path, JSON.stringify({ environment }));
    return path;
  };
  const strict = await write('strict.json', { map: 'studio.exr' });
  await rejectsWith(loadSceneFile(strict), 'INVALID_SCENE_FILE', 'environment.map');
  const reports: string[] = [];
  const zeroed = await loadSceneFile(strict, { negativeTexels: 'zero', onNegativeTexels: (r, field) => reports.push(`${field}:${r.channels > 0}`) });
  assert.ok(zeroed.scene.environmentMap !== undefined);
  assert.deepEqual(reports, ['environment.map:true']);
  assert.ok((await loadSceneFile(await write('zero.json', { map: 'studio.exr', negativeTexels: 'zero' }))).scene.environmentMap !== undefined);
  await rejectsWith(loadSceneFile(await write('error.json', { map: 'studio.exr', negativeTexels: 'error' }), { negativeTexels: 'zero' }), 'INVALID_SCENE_FILE', 'environment.map');
  assert.throws(() => parseSceneFile(JSON.stringify({ environment: { map: 'a.exr', negativeTexels: 'clamp' } })), (e: unknown) => e instanceof GpuRendererError && e.field === 'environment.negativeTexels');
  assert.throws(() => parseSceneFile(JSON.stringify({ environment: { color: [1, 1, 1], negativeTexels: 'zero' } })), (e: unknown) => e instanceof GpuRendererError && e.field === 'environment.negativeTexels');
});
