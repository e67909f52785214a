// The linked programs respect WebGPU's default limits by construction: every kernel binds at most
// 8 storage buffers per stage and uses at most 4 bind groups, and its bindings are exactly those of
// the binding table (reflection of the linked WGSL, not a hand-kept list).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { bindingTables } from '../../scripts/shader-build/binding-tables.ts';
import { generatedPrograms } from '../../src/shaders/programs.generated.ts';
import { programWgsl } from '../../src/shaders/program-wgsl.ts';
import { programGroups, programSpecs, type ProgramName } from '../../src/shaders/programs.ts';
import { shaderFeatures } from '../../src/shaders/features.ts';
import { createWavefrontPathTracingComputeShaderSource } from '../../src/pathtracer/index.ts';
import { testDevice } from '../helpers/gpu.ts';

// The megakernel (integrator: 'megakernel', opt-in) runs a whole path in one kernel and binds more
// than the default 8 storage buffers: the renderer requests up to 16 from the adapter and, on a
// device below the kernel's count, runs the wavefront instead and says so
// (test/pathtracer/megakernel.test.ts).
const storageLimitAboveDefault: Partial<Record<ProgramName, number>> = { megakernel: 16 };

test('every program binds within WebGPU default limits (the opt-in megakernel within what the renderer requests) and only table bindings', () => {
  for (const [name, spec] of Object.entries(programSpecs)) {
    const program = generatedPrograms[name as keyof typeof generatedPrograms];
    const table = bindingTables[spec.group];
    const storage = program.bindings.filter((b) => table[b]!.kind === 'storage').length;
    assert.ok(storage <= (storageLimitAboveDefault[name as ProgramName] ?? 8), `${name} binds ${storage} storage buffers`);
    assert.ok(Math.max(...program.bindings.map((b) => table[b]!.group)) < 4, `${name} uses more than 4 bind groups`);
    for (const o of program.overrides) assert.ok(o in shaderFeatures, `${name}: override ${o} is a shader feature`);
  }
});

test('the shipped WGSL of every program compiles on WebGPU without errors', async () => {
  const device = await testDevice();
  for (const name of Object.keys(programSpecs) as ProgramName[]) {
    const code = await programWgsl(name);
    // The half-precision OIDN programs need the shader-f16 feature (the runtime picks f32 without it).
    if (/^enable f16;/m.test(code) && !device.features.has('shader-f16')) continue;
    const info = await device.createShaderModule({ code }).getCompilationInfo();
    assert.deepEqual(info.messages.filter((m) => m.type === 'error').map((m) => m.message), [], name);
  }
});

test('the public shader source is exactly the programs of the groups marked shaderSource', async () => {
  const sources: Record<string, string> = createWavefrontPathTracingComputeShaderSource();
  const eager = (Object.keys(programSpecs) as ProgramName[]).filter((name) => programGroups[programSpecs[name].group].shaderSource);
  assert.deepEqual(Object.keys(sources).sort(), eager.sort());
  for (const name of eager) assert.equal(sources[name], await programWgsl(name), name);
  assert.ok(eager.includes('shade') && eager.includes('present'));
});
