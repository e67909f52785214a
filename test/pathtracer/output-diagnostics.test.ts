// Frame diagnostics against constructed scenes: terminal radiance of an emitter-only and an
// environment-only view equals the known radiance; every path ends in exactly one termination
// counter; legacy-clamp-equivalent samples; dispatch counts and guardrails follow the wave plan and
// the submission bound (which does not change the image); feature flags; linear presentation and
// exposure in EV; invalid contributions dropped and counted per contribution and per sample.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createWavefrontPathTracingComputeRenderer } from '../../src/pathtracer/index.ts';
import { transportExperimentNames } from '../../src/pathtracer/feature-flags.ts';
import { encodeRadianceToRgba8 } from '../../src/film/tone-mapping.ts';
import { GpuRendererError } from '../../src/errors/gpu-renderer-error.ts';
import { pathTracerBindings } from '../../src/gpu-layout/bindings.ts';
import { LUMINANCE_FRACTION_BITS, queueBufferWords, queueCounterSlots } from '../../src/gpu-layout/constants.ts';
import { filmAovPixelLayout, filmMomentsLayout, filmPixelLayout, frameUniformsLayout, pathRecordLayout, waveUniformsLayout } from '../../src/gpu-layout/records.ts';
import { allocateStructArray, writeStruct } from '../../src/gpu-layout/struct-layout.ts';
import { BufferUsage } from '../../src/gpu/webgpu-constants.ts';
import { generatedPrograms } from '../../src/shaders/programs.generated.ts';
import { programWgsl } from '../../src/shaders/program-wgsl.ts';
import { readBuffer, testDevice, uploadBuffer } from '../helpers/gpu.ts';
import { runTestProgram } from '../helpers/wgsl.ts';
import { cornellRenderer, luminance, rect, squareCamera } from './output-helpers.ts';

const emitter = (radiance: [number, number, number]) => ({ baseColorFactor: [0, 0, 0, 1] as [number, number, number, number], emissiveFactor: radiance, emissiveStrength: 1 });

test('terminal radiance: an emitter filling the view and an environment-only view give their known luminance', async () => {
  const device = await testDevice();
  const L: [number, number, number] = [3, 1.5, 0.25];
  const lit = await createWavefrontPathTracingComputeRenderer({ device, width: 16, height: 16, samplesPerPixel: 4, camera: squareCamera, meshes: [rect(-2, -2, 2, 2, emitter(L))] });
  const sky = await createWavefrontPathTracingComputeRenderer({ device, width: 16, height: 16, samplesPerPixel: 4, camera: squareCamera, environment: { color: [0.5, 2, 1] } });
  try {
    const a = await lit.renderFrame();
    assert.equal(a.terminalRadiance.samples, 16 * 16 * 4);
    assert.ok(Math.abs(a.terminalRadiance.emitterLuminance / luminance(...L) - 1) < 1e-5, JSON.stringify(a.terminalRadiance));
    assert.ok(Math.abs(a.terminalRadiance.totalLuminance / luminance(...L) - 1) < 1e-5);
    assert.equal(a.terminalRadiance.environmentLuminance, 0);
    assert.ok(a.terminalRadiance.directLightLuminance < 1e-5 * luminance(...L));
    assert.equal(a.terminalRadiance.ambientResidualLuminance, 0);
    assert.equal(a.terminalRadiance.ambientResidualShare, 0);
    // Continuations off the black emitter escape into the black environment or end: no more light.
    const t = a.terminations;
    assert.equal(t.escaped + t.absorbed + t.invalidBsdfSample + t.russianRoulette + t.maxDepth + t.invalidThroughput, a.rays.camera);
    const b = await sky.renderFrame();
    assert.ok(Math.abs(b.terminalRadiance.environmentLuminance / luminance(0.5, 2, 1) - 1) < 1e-5, JSON.stringify(b.terminalRadiance));
    assert.equal(b.terminalRadiance.emitterLuminance, 0);
    assert.equal(b.terminations.escaped, b.rays.camera);
    // No channel above 4: the legacy clamp would not have touched these samples.
    assert.equal(a.radianceDiagnostics.legacyClampEquivalentSamples, 0);
  } finally {
    lit.destroy();
    sky.destroy();
  }
  const bright = await createWavefrontPathTracingComputeRenderer({ device, width: 8, height: 8, samplesPerPixel: 2, camera: squareCamera, meshes: [rect(-2, -2, 2, 2, emitter([5, 0, 0]))] });
  try {
    const s = await bright.renderFrame();
    assert.equal(s.radianceDiagnostics.legacyClampEquivalentSamples, s.rays.camera, 'every sample has a channel above 4 (counted, not clamped)');
    assert.ok(Math.abs((await bright.readRadiance()).data[0]! - 5) < 1e-6);
  } finally {
    bright.destroy();
  }
});

test('every path ends in exactly one termination; the luminance split adds up; no invalid samples in a valid scene', async () => {
  const renderer = await cornellRenderer(16, { seed: 6, maxDepth: 4 });
  try {
    const s = await renderer.renderFrame({ samplesPerPixel: 8 });
    const t = s.terminations;
    assert.equal(t.russianRoulette + t.maxDepth + t.escaped + t.absorbed + t.invalidBsdfSample + t.invalidThroughput, s.rays.camera, JSON.stringify(t));
    assert.ok(t.maxDepth > 0 && t.escaped > 0);
    assert.equal(s.invalidSamples, 0);
    assert.deepEqual(s.radianceDiagnostics, { invalidSamples: 0, invalidContributions: 0, legacyClampEquivalentSamples: s.radianceDiagnostics.legacyClampEquivalentSamples });
    const r = s.terminalRadiance;
    assert.ok(r.emitterLuminance > 0 && r.directLightLuminance > 0 && r.environmentLuminance === 0);
    // The mean luminance per sample equals the image's mean luminance (every pixel took 8 samples).
    const image = (await renderer.readRadiance()).data;
    let mean = 0;
    for (let p = 0; p < 256; p++) mean += luminance(image[4 * p]!, image[4 * p + 1]!, image[4 * p + 2]!);
    assert.ok(Math.abs(r.totalLuminance / (mean / 256) - 1) < 1e-4, `${r.totalLuminance} vs ${mean / 256}`);
    assert.ok(Math.abs(r.emitterLuminance + r.environmentLuminance + r.directLightLuminance - r.totalLuminance) < 1e-6 * r.totalLuminance);
  } finally {
    renderer.destroy();
  }
});

test('gpuParallelism and transportGuardrails follow the wave plan; the submission bound does not change the image', async () => {
  const maxDepth = 3;
  const a = await cornellRenderer(16, { seed: 2, maxDepth, maxFramePassesPerSubmission: 3 });
  const b = await cornellRenderer(16, { seed: 2, maxDepth });
  try {
    const s = await a.renderFrame({ samplesPerPixel: 2 });
    const waves = (256 * 2) / 64; // 256 pixels x 2 samples in waves of tileSize^2 = 64 paths
    assert.equal(s.waves, waves);
    assert.equal(s.transportGuardrails.jobsPerFrame, waves);
    // ceil(8 / 3) wave submissions and the closing one (statistics copy, presentation).
    assert.equal(s.transportGuardrails.submissions, 4);
    assert.equal(s.transportGuardrails.jobsPerSubmission, waves / 4);
    assert.equal(s.transportGuardrails.queueOverflow, 0);
    assert.equal(s.transportGuardrails.deviceLost, false);
    assert.equal(s.transportGuardrails.trackedMemoryBytes, s.memory.totalBytes);
    assert.ok(s.transportGuardrails.jobsPerSecond > 0);
    const g = s.gpuParallelism;
    // Per wave: camera, bounce 0's traversal and shading, per later bounce a traversal and the
    // one-invocation dispatch sizing its shading, and the accumulation, all direct; the shading of
    // bounces 1..maxDepth is indirect (sized on the GPU from its queue).
    assert.equal(g.directDispatches, waves * (4 + 2 * maxDepth));
    assert.equal(g.indirectDispatches, waves * maxDepth);
    assert.equal(g.largestEstimatedIndirectWorkgroupsPerDispatch, 1, 'an indirect shading dispatch covers at most the wave (64 paths)');
    assert.equal(s.wavePaths, 64);
    assert.equal(g.largestDirectWorkgroupsPerDispatch, 2, '64 paths per wave: a traversal grid covers 64 rays and 64 shadow rays');
    assert.equal(g.physicalCoreCount, null);
    assert.ok(g.adapterLimits.maxComputeInvocationsPerWorkgroup >= 64 && g.workgroupSize === 64);
    assert.equal(s.maxFramePassesPerSubmission, 3);
    await b.renderFrame({ samplesPerPixel: 2 });
    assert.deepEqual((await a.readRadiance()).data, (await b.readRadiance()).data);
  } finally {
    a.destroy();
    b.destroy();
  }
});

test('feature flags: mirrored names accepted and reported, bias refused, experiments packed into a bitfield', async () => {
  const device = await testDevice();
  const renderer = await createWavefrontPathTracingComputeRenderer({
    device, width: 4, height: 4,
    featureFlags: {
      'renderer.transport.physicalEstimator': true,
      'renderer.transport.strictPhysicalLowSppLighting': true,
      'renderer.transport.deterministicLowSppIndirect.enabled': true,
      'renderer.diagnostics.productTransportTelemetry.enabled': true,
    },
  });
  try {
    const s = await renderer.renderFrame();
    const snap = renderer.getSnapshot();
    for (const state of [s, snap]) {
      assert.deepEqual(
        { requested: state.featureFlags['renderer.transport.physicalEstimator']!.requested, effective: state.featureFlags['renderer.transport.physicalEstimator']!.effective },
        { requested: true, effective: true },
      );
      assert.deepEqual(state.transportExperiments.deterministicLowSppIndirect, { requested: true, effective: false }, 'a bias-adding experiment is a no-op');
      assert.deepEqual(state.transportExperiments.productTransportTelemetry, { requested: true, effective: true });
      assert.deepEqual(state.transportExperiments.stableSampleRouting, { requested: false, effective: true });
      const keys = Object.keys(transportExperimentNames);
      const expected = keys.reduce((bits, key, i) => (state.transportExperiments[key as keyof typeof transportExperimentNames].effective ? bits | (1 << i) : bits), 0);
      assert.equal(state.transportExperimentFlags, expected);
      assert.equal(state.transportExperimentRequestedFlags, (1 << keys.indexOf('deterministicLowSppIndirect')) | (1 << keys.indexOf('productTransportTelemetry')));
    }
  } finally {
    renderer.destroy();
  }
  const refused = (flags: Record<string, unknown>, code: string, field: string) =>
    assert.rejects(createWavefrontPathTracingComputeRenderer({ device, width: 4, height: 4, featureFlags: flags } as never), (e: unknown) => e instanceof GpuRendererError && e.code === code && e.field === field);
  await refused({ 'renderer.transport.physicalEstimator': false }, 'BIASED_TRANSPORT_REFUSED', 'featureFlags["renderer.transport.physicalEstimator"]');
  await refused({ 'renderer.transport.strictPhysicalLowSppLighting': false }, 'BIASED_TRANSPORT_REFUSED', 'featureFlags["renderer.transport.strictPhysicalLowSppLighting"]');
  await refused({ 'renderer.transport.ambientFloor': true }, 'INVALID_OPTION', 'featureFlags["renderer.transport.ambientFloor"]');
  await refused({ 'renderer.transport.stableSampleRouting.enabled': 1 }, 'INVALID_OPTION', 'featureFlags["renderer.transport.stableSampleRouting.enabled"]');
});

test('presentation: linear output shows exposed linear radiance, tone mapped output matches the CPU encoder; exposure in EV', async () => {
  const device = await testDevice();
  const L: [number, number, number] = [0.1, 0.25, 0.4];
  const scene = { device, width: 4, height: 4, samplesPerPixel: 1, camera: squareCamera, meshes: [rect(-2, -2, 2, 2, emitter(L))] };
  const linear = await createWavefrontPathTracingComputeRenderer({ ...scene, presentationOutput: 'linear', exposureEv: 1 });
  const mapped = await createWavefrontPathTracingComputeRenderer({ ...scene, toneMapping: 'agx', exposure: 1.5, exposureEv: -0.5 });
  try {
    await linear.renderFrame();
    await mapped.renderFrame();
    const a = (await linear.readPixels()).data;
    L.forEach((v, c) => assert.equal(a[c], Math.floor(0.5 + 255 * Math.min(1, 2 * v)), `linear channel ${c}`));
    const b = (await mapped.readPixels()).data;
    const cpu = encodeRadianceToRgba8(new Float32Array([...L, 1]), { toneMapping: 'agx', exposure: 1.5, exposureEv: -0.5 });
    for (let c = 0; c < 3; c++) assert.ok(Math.abs(b[c]! - cpu[c]!) <= 1, `channel ${c}: GPU ${b[c]} CPU ${cpu[c]}`);
    assert.equal(linear.getSnapshot().presentationOutput, 'linear');
    assert.equal(linear.getSnapshot().exposureEv, 1);
    // Scene-referred reads never see the display transform.
    assert.ok(Math.abs((await linear.readRadiance()).data[1]! - 0.25) < 1e-6);
  } finally {
    linear.destroy();
    mapped.destroy();
  }
  for (const [options, field] of [[{ presentationOutput: 'srgb' }, 'presentationOutput'], [{ exposureEv: Number.POSITIVE_INFINITY }, 'exposureEv']] as const) {
    await assert.rejects(createWavefrontPathTracingComputeRenderer({ ...scene, ...options } as never), (e: unknown) => e instanceof GpuRendererError && e.field === field);
  }
});

test('invalid contributions are dropped and counted, and each sample that lost one counts once (commit + accumulate kernels)', async () => {
  const device = await testDevice();
  const slots = 8;
  // Per slot, the contributions committed in order (NaN, Inf and negative values are invalid).
  const schedule: [number, number, number][][] = [
    [[1, 2, 3]],
    [[Number.NaN, 0, 0]],
    [[Infinity, 1, 1]],
    [[-1, 0, 0]],
    [[Number.NaN, 1, 1], [0.5, 0.5, 0.5], [1, -Infinity, 1]],
    [], [], [[6, 0, 0]],
  ];
  const flat = schedule.flatMap((list, slot) => list.map((v) => [...v, slot]));
  const inputs = uploadBuffer(device, new Float32Array(flat.flat()));
  // One 8-path full-frame wave of an 8x1 image: path i at pixel i, sample 0.
  const records = allocateStructArray(pathRecordLayout, slots);
  for (let i = 0; i < slots; i++) writeStruct(pathRecordLayout, new DataView(records), i, { state: { pixel: i, sampleIndex: 0 } });
  const paths = uploadBuffer(device, records);
  const queues = uploadBuffer(device, new Uint32Array(queueBufferWords(slots)));
  await runTestProgram(device, {
    source: `import package::pathtracer::radiance::commit_radiance;
@group(0) @binding(0) var<storage, read> inputs: array<vec4f>;
@compute @workgroup_size(1) fn main() {
  for (var i = 0u; i < arrayLength(&inputs); i++) { commit_radiance(u32(inputs[i].w), inputs[i].xyz); }
}`,
    resources: { inputs, paths, queues },
    workgroups: 1,
  });
  // The shipped accumulation kernel over that wave.
  const wave = new ArrayBuffer(waveUniformsLayout.size);
  writeStruct(waveUniformsLayout, new DataView(wave), 0, { firstPath: 0, firstSample: 0, pathCount: slots, list: 0 });
  const frame = new ArrayBuffer(frameUniformsLayout.size);
  writeStruct(frameUniformsLayout, new DataView(frame), 0, { imageSize: [slots, 1] });
  const film = uploadBuffer(device, new Float32Array((slots * filmPixelLayout.size) / 4));
  const resources: Record<string, GPUBuffer> = {
    paths, queues, film, frame: uploadBuffer(device, frame, BufferUsage.UNIFORM),
    filmAovs: uploadBuffer(device, new Float32Array((slots * filmAovPixelLayout.size) / 4)), filmMoments: uploadBuffer(device, new Float32Array((slots * filmMomentsLayout.size) / 4)),
    filmIds: uploadBuffer(device, new Uint32Array(slots)), adaptivePixels: uploadBuffer(device, new Uint32Array(8)),
    wave: uploadBuffer(device, wave, BufferUsage.UNIFORM),
  };
  const program = generatedPrograms.accumulate;
  const module = device.createShaderModule({ code: await programWgsl('accumulate') });
  const pipeline = await device.createComputePipelineAsync({ layout: 'auto', compute: { module, entryPoint: 'accumulate_samples' } });
  const encoder = device.createCommandEncoder();
  const pass = encoder.beginComputePass();
  pass.setPipeline(pipeline);
  const spec = (name: string) => pathTracerBindings[name as keyof typeof pathTracerBindings];
  for (const group of new Set(program.bindings.map((name) => spec(name).group))) {
    pass.setBindGroup(group, device.createBindGroup({
      layout: pipeline.getBindGroupLayout(group),
      entries: program.bindings.filter((name) => spec(name).group === group).map((name) => ({ binding: spec(name).binding, resource: { buffer: resources[name]! } })),
    }));
  }
  pass.dispatchWorkgroups(1);
  pass.end();
  device.queue.submit([encoder.finish()]);
  const c = new Uint32Array(await readBuffer(device, queues));
  const f = new Float32Array(await readBuffer(device, film));
  assert.equal(c[queueCounterSlots.invalidSamples], 5, 'contributions dropped');
  assert.equal(c[queueCounterSlots.invalidPathSamples], 4, 'samples that lost a contribution');
  assert.equal(c[queueCounterSlots.clampEquivalentSamples], 1, 'the sample of radiance 6');
  const expected = [[1, 2, 3], [0, 0, 0], [0, 0, 0], [0, 0, 0], [0.5, 0.5, 0.5], [0, 0, 0], [0, 0, 0], [6, 0, 0]];
  expected.forEach((rgb, p) => assert.deepEqual([...f.subarray(4 * p, 4 * p + 4)], [...rgb, 1], `pixel ${p}: valid contributions kept, every sample counted`));
  const total = expected.reduce((sum, [r, g, b]) => sum + luminance(r!, g!, b!), 0);
  const fixed = (c[queueCounterSlots.totalLuminanceLo]! + c[queueCounterSlots.totalLuminanceHi]! * 2 ** 32) / 2 ** LUMINANCE_FRACTION_BITS;
  assert.ok(Math.abs(fixed - total) <= 1 / 2 ** LUMINANCE_FRACTION_BITS, `${fixed} vs ${total}`);
});
