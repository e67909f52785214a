// Mutation fuzzing of the public boundary: thousands of randomly damaged scene files go through the
// scene-file parser, the option and scene validators and the CPU scene preparation (BVH, material
// heap, light table). Every failure must be a typed GpuRendererError naming a field, and everything
// that passes must pack into finite GPU data (no RangeError from the alias table, no Infinity).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { GpuRendererError } from '../../src/errors/gpu-renderer-error.ts';
import { createWavefrontPathTracingComputeConfig } from '../../src/pathtracer/config.ts';
import { prepareScene } from '../../src/pathtracer/scene/prepare-scene.ts';
import { createCornellBoxScene } from '../../src/scene/cornell-box.ts';
import { normalizeWavefrontScene } from '../../src/scene/normalize-scene.ts';
import { parseSceneFile } from '../../src/scene/scene-file.ts';
import { resolveSceneFile } from '../../src/io/scene-file-loader.ts';
import { rng } from '../helpers/random.ts';
import { lightRecordLayout } from '../../src/gpu-layout/records.ts';
import { fieldOf } from '../../src/gpu-layout/struct-layout.ts';

type Json = null | boolean | number | string | Json[] | { [key: string]: Json };

/** A scene with every kind of part: inline and shared materials, instances, a texture, objects. */
function seedScene(): Json {
  const cornell = JSON.parse(JSON.stringify(createCornellBoxScene())) as { [key: string]: Json };
  return {
    ...cornell,
    materials: [{ baseColorFactor: [0.5, 0.5, 0.5, 1], metallicFactor: 0.2, roughnessFactor: 0.4, baseColorTexture: { index: 0, transform: { offset: [0.1, 0], scale: [2, 2] } }, alphaMode: 'MASK' }],
    textures: [{ image: 0, sampler: { wrapS: 'mirrored-repeat', magFilter: 'nearest' } }],
    images: [{ width: 2, height: 2, data: [255, 0, 0, 255, 0, 255, 0, 0, 0, 0, 255, 255, 255, 255, 255, 128] }],
    instances: [
      { mesh: 0 }, { mesh: 1 }, { mesh: 2 }, { mesh: 3 }, { mesh: 4 }, { mesh: 5 }, { mesh: 6 }, { mesh: 7 },
      { mesh: 5, material: 0, transform: [0.5, 0, 0, 0, 0, -0.5, 0, 0, 0, 0, 0.5, 0, 0.2, 0.3, 0.1, 1] },
    ],
    sceneObjects: [{ type: 'sphere', center: [0, 0, 0], radius: 0.2, color: [0.9, 0.9, 0.9], emission: [1, 1, 1, 0.5] }],
  };
}

const replacements: Json[] = [0, -1, 1, 2, 0.5, 1e-30, 1e38, 3.4e38, -3.4e38, 1e20, 255, 256, 1.5, 65536, 4294967296, -0, '1', null, true, [], {}, [1, 2, 3], 'repeat', 'MASK'];

function mutate(value: Json, random: () => number, depth = 0): Json {
  if (Array.isArray(value)) {
    if (value.length > 0 && random() < 0.85) {
      const copy = [...value];
      const i = Math.floor(random() * copy.length);
      const r = random();
      if (r < 0.08) copy.splice(i, 1);
      else if (r < 0.14) copy.push(copy[i]!);
      else copy[i] = mutate(copy[i]!, random, depth + 1);
      return copy;
    }
    return replacements[Math.floor(random() * replacements.length)]!;
  }
  if (value !== null && typeof value === 'object') {
    const keys = Object.keys(value);
    if (keys.length > 0 && random() < 0.9) {
      const copy = { ...value };
      const key = keys[Math.floor(random() * keys.length)]!;
      if (random() < 0.08) delete copy[key];
      else copy[key] = mutate(copy[key]!, random, depth + 1);
      return copy;
    }
    return replacements[Math.floor(random() * replacements.length)]!;
  }
  return replacements[Math.floor(random() * replacements.length)]!;
}

function assertFinite(buffer: ArrayBuffer, what: string): void {
  const f = new Float32Array(buffer);
  for (let i = 0; i < f.length; i++) {
    // Integer fields (ids, offsets, flags) alias as floats: only NaN/Inf bit patterns of real floats
    // matter, and INDEX_NONE (0xffffffff) is a NaN pattern, so check the exponent of non-index words.
    if (!Number.isFinite(f[i]!) && new Uint32Array(buffer, i * 4, 1)[0] !== 0xffffffff) assert.fail(`${what}: word ${i} is ${f[i]}`);
  }
}

test('2000 mutated scene files give typed errors naming a field, or finite GPU data', async () => {
  const random = rng(2024);
  const seed = seedScene();
  let rejected = 0;
  let prepared = 0;
  for (let iteration = 0; iteration < 2000; iteration++) {
    let scene = seed;
    const edits = 1 + Math.floor(random() * 3);
    for (let e = 0; e < edits; e++) scene = mutate(scene, random);
    try {
      const { scene: description } = await resolveSceneFile(parseSceneFile(JSON.stringify(scene)));
      createWavefrontPathTracingComputeConfig({ width: 8, height: 8, ...description });
      const normalized = normalizeWavefrontScene(description);
      const p = await prepareScene(normalized, { maxTextureDimension2D: 64, maxTextureArrayLayers: 4 });
      // The vertex streams are copies of the validated mesh arrays plus integer encodings (octahedral
      // normals, unorm colours) whose words alias NaN patterns: the float records below are derived.
      for (const [name, data] of Object.entries({ primitives: p.primitives, bvhNodes: p.bvhNodes, instances: p.instances, materials: p.materials, lights: p.lights })) {
        assertFinite(data, `iteration ${iteration} ${name}`);
      }
      if (p.lightCount > 0) {
        const pmf = new Float32Array(p.lights);
        let total = 0;
        const at = fieldOf(lightRecordLayout, 'pmf').offset / 4;
        for (let l = 0; l < p.lightCount; l++) total += pmf[(l * lightRecordLayout.size) / 4 + at]!;
        assert.ok(Math.abs(total - 1) < 1e-4, `iteration ${iteration}: light pmfs sum to ${total}`);
      }
      prepared++;
    } catch (error) {
      if (!(error instanceof GpuRendererError)) throw new Error(`iteration ${iteration}: untyped ${String(error)}\n${JSON.stringify(scene).slice(0, 400)}`, { cause: error });
      rejected++;
      if (error.field !== undefined) assert.ok(error.message.startsWith(`${error.field}: `), `iteration ${iteration}: message names the field`);
    }
  }
  assert.ok(rejected > 500 && prepared > 200, `${rejected} rejected, ${prepared} prepared`);
});
