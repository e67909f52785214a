import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createRayTracingRenderPlan, renderPlanMaxDepthLimit } from '../../src/planning/render-plan.ts';
import { russianRouletteSurvivalProbability } from '../../src/planning/russian-roulette.ts';
import {
  materialCoreLayout,
  pathStateLayout,
  rayWorkItemLayout,
  rendererWavefrontAccumulationTexelBytes,
  sampleRecordLayout,
  pathHitLayout,
  pathRecordLayout,
  surfaceRecordLayout,
  wavefrontRecordLayouts,
} from '../../src/gpu-layout/records.ts';
import { allocateStructArray, readStruct, writeStruct, type StructLayout } from '../../src/gpu-layout/struct-layout.ts';
import { BufferUsage } from '../../src/gpu/webgpu-constants.ts';
import { GpuRendererError } from '../../src/errors/gpu-renderer-error.ts';
import { readBuffer, testDevice, uploadBuffer } from '../helpers/gpu.ts';
import { runTestProgram } from '../helpers/wgsl.ts';

test('the plan exposes the snapshot boundary, RT-first stage order, bands and AS policy', () => {
  const plan = createRayTracingRenderPlan({ snapshotId: 'visual-snapshot-42' });
  assert.equal(plan.snapshotId, 'visual-snapshot-42');
  assert.equal(plan.inputBoundary.kind, 'stable-visual-snapshot');
  assert.equal(plan.inputBoundary.snapshotId, 'visual-snapshot-42');
  const keys = plan.renderStages.map((s) => s.key);
  plan.renderStages.forEach((stage, i) => {
    assert.equal(stage.order, i);
    for (const dep of stage.dependsOn) assert.ok(keys.indexOf(dep) < i, `${dep} precedes ${stage.key}`);
  });
  for (const consumer of plan.inputBoundary.consumedBy) assert.ok(keys.includes(consumer));
  // Ray tracing comes first: the first ray-tracing stage precedes every shading stage, and the
  // acceleration structure is ready before any ray is traced.
  const firstTrace = plan.renderStages.findIndex((s) => s.tracesRays);
  assert.ok(firstTrace > keys.indexOf('accelerationUpdate'));
  assert.ok(firstTrace < keys.indexOf('materialEvaluation') && firstTrace < keys.indexOf('scatter'));
  // Bands tile the distance axis without gaps.
  plan.representationBands.forEach((band, i) => {
    assert.ok(band.endDistance > band.startDistance);
    if (i > 0) assert.equal(band.startDistance, plan.representationBands[i - 1]!.endDistance);
  });
  assert.equal(plan.representationBands[0]!.startDistance, 0);
  assert.equal(plan.representationBands.at(-1)!.endDistance, Infinity);
  assert.equal(plan.accelerationStructure.nodeContract.layout, wavefrontRecordLayouts.BvhNode);
  assert.equal(plan.accelerationStructure.primitiveContract.layout, wavefrontRecordLayouts.Primitive);
  assert.equal(plan.accelerationStructure.updatePolicy.staticGeometry, 'build-once-reuse');
  assert.ok(Object.isFrozen(plan.wavefront.contracts) && Object.isFrozen(plan.renderStages[0]));
  assert.throws(() => {
    (plan.renderStages as unknown[]).pop();
  }, TypeError);
});

test('wavefront contracts are the very record layouts of records.ts; queue capacity is tileSize^2', () => {
  const plan = createRayTracingRenderPlan({ snapshotId: 's', tileSize: 64, maxDepth: 12 });
  const c = plan.wavefront.contracts;
  assert.equal(c.path.layout, pathStateLayout);
  assert.equal(c.ray.layout, rayWorkItemLayout);
  assert.equal(c.hit.layout, pathHitLayout);
  assert.equal(c.record.layout, pathRecordLayout);
  assert.equal(c.surface.layout, surfaceRecordLayout);
  assert.equal(c.material.layout, materialCoreLayout);
  assert.equal(c.sample.layout, sampleRecordLayout);
  assert.equal(c.medium.field, pathStateLayout.fields.find((f) => f.name === 'media'));
  assert.equal(c.medium.stackLimit, 4);
  assert.equal(c.accumulation.bytes, rendererWavefrontAccumulationTexelBytes);
  assert.equal(c.accumulation.bytes, 16);
  for (const contract of [c.path, c.ray, c.hit, c.surface, c.material, c.shadowRay, c.sample, c.record]) {
    assert.equal(contract.bytes, contract.layout.size);
    assert.equal(contract.version, contract.layout.version);
    assert.equal(wavefrontRecordLayouts[contract.name as keyof typeof wavefrontRecordLayouts], contract.layout);
  }
  const q = plan.wavefront.queueLayout;
  assert.equal(q.strategy, 'path-records-slot-queues');
  assert.equal(q.capacity, 64 * 64);
  assert.equal(q.pathRecordBytes, pathRecordLayout.size);
  assert.equal(q.hitRecordBytes, pathHitLayout.size);
  assert.equal(createRayTracingRenderPlan({ snapshotId: 's' }).wavefront.queueLayout.capacity, 256 * 256);
  const t = plan.wavefront.termination;
  assert.deepEqual([...t.completion], ['emissive', 'environment']);
  assert.equal(t.maxDepth, 12);
  assert.equal(createRayTracingRenderPlan({ snapshotId: 's' }).wavefront.termination.maxDepth, 8);
  assert.equal(t.maxDepthLimit, renderPlanMaxDepthLimit);
  assert.equal(t.russianRoulette.startDepth, 3);
});

// Distinct, exactly representable values so any offset mistake shows.
function sample(layout: StructLayout): Record<string, number[]> {
  const values: Record<string, number[]> = {};
  layout.fields.forEach((f, i) => {
    values[f.name] = Array.from({ length: f.components }, (_, k) => (f.scalar === 'f32' ? 0.25 + i * 8 + k : 7 + i * 8 + k));
  });
  return values;
}

test('records packed with the plan contracts read back field by field through a WGSL kernel', async () => {
  const device = await testDevice();
  const c = createRayTracingRenderPlan({ snapshotId: 'gpu' }).wavefront.contracts;
  for (const contract of [c.path, c.ray, c.hit, c.surface, c.material, c.sample]) {
    const layout = contract.layout;
    const data = allocateStructArray(layout, 2);
    const view = new DataView(data);
    writeStruct(layout, view, 0, sample(layout));
    writeStruct(layout, view, 1, sample(layout));
    const words = layout.fields.reduce((n, f) => n + f.components, 0);
    const lines = layout.fields.flatMap((f) =>
      Array.from({ length: f.components }, (_, k) => `  out[w] = bitcast<u32>(src[1].${f.name}${f.components > 1 ? `[${k}]` : ''}); w += 1u;`),
    );
    const code = `import package::layout::records::${contract.name};
@group(0) @binding(0) var<storage, read> src: array<${contract.name}>;
@group(0) @binding(1) var<storage, read_write> out: array<u32>;
@compute @workgroup_size(1) fn main() {
  var w = 0u;
${lines.join('\n')}
}`;
    const src = uploadBuffer(device, data);
    const out = device.createBuffer({ size: words * 4, usage: BufferUsage.STORAGE | BufferUsage.COPY_SRC });
    await runTestProgram(device, { source: code, resources: { src, out }, workgroups: 1 });
    const got = new DataView(await readBuffer(device, out));
    const expected = readStruct(layout, view, 1);
    let w = 0;
    for (const f of layout.fields) {
      const comps = ([] as number[]).concat(expected[f.name] as number | number[]);
      for (const value of comps) {
        assert.equal(f.scalar === 'f32' ? got.getFloat32(w * 4, true) : got.getUint32(w * 4, true), value, `${contract.name}.${f.name}`);
        w++;
      }
    }
    src.destroy();
    out.destroy();
  }
  // The medium stack field: the plan's offset addresses the word a kernel writes.
  const data = allocateStructArray(pathStateLayout, 1);
  const code = `import package::layout::records::PathState;
@group(0) @binding(0) var<storage, read_write> paths: array<PathState>;
@compute @workgroup_size(1) fn main() {
  paths[0].media = 0x04030201u;
}`;
  const buffer = uploadBuffer(device, data);
  await runTestProgram(device, { source: code, resources: { paths: buffer }, workgroups: 1 });
  const back = new DataView(await readBuffer(device, buffer));
  assert.equal(back.getUint32(c.medium.field.offset, true), 0x04030201);
  buffer.destroy();
});

test('invalid plan options are typed errors naming the field', () => {
  const isField = (field: string) => (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_OPTION' && e.field === field;
  assert.throws(() => createRayTracingRenderPlan({ snapshotId: '' }), isField('snapshotId'));
  assert.throws(() => createRayTracingRenderPlan({ snapshotId: 's', profile: 'vr' as never }), isField('profile'));
  assert.throws(() => createRayTracingRenderPlan({ snapshotId: 's', maxDepth: renderPlanMaxDepthLimit + 1 }), isField('maxDepth'));
  assert.throws(() => createRayTracingRenderPlan({ snapshotId: 's', tileSize: 3 }), isField('tileSize'));
});

test('Russian roulette survival follows the plan policy', () => {
  assert.equal(russianRouletteSurvivalProbability([0.1, 0.1, 0.1], 1, 2, 3), 1, 'no roulette before startDepth');
  assert.equal(russianRouletteSurvivalProbability([0.2, 0.6, 0.1], 1, 3, 3), 0.6);
  assert.equal(russianRouletteSurvivalProbability([0.2, 0.6, 0.1], 2.25, 5, 3), 1, 'eta^2 scaling lifts paths inside glass');
  assert.equal(russianRouletteSurvivalProbability([0.2, 0.3, 0.1], 2, 5, 3), 0.6);
});
