import { test } from 'node:test';
import assert from 'node:assert/strict';
import {
  getRendererWorkerManifest,
  getRendererWorkerProfile,
  rendererWorkerManifests,
  rendererWorkerProfileNames,
  rendererWorkerProfiles,
} from '../../src/planning/worker-manifests.ts';
import { defaultRendererWorkerProfile, rendererDebugOwner, rendererWorkerQueueClass } from '../../src/planning/worker-constants.ts';
import { topologicalJobOrder } from '../../src/planning/validate-manifest.ts';
import type { RendererWorkerJob } from '../../src/planning/worker-manifest-types.ts';
import { GpuRendererError } from '../../src/errors/gpu-renderer-error.ts';

test('profiles publish the documented stages in order', () => {
  assert.deepEqual(getRendererWorkerManifest().jobs.map((j) => j.key), ['acquire', 'visibility', 'mainEncode', 'postProcess', 'submit']);
  assert.deepEqual(getRendererWorkerManifest('xr').jobs.map((j) => j.key), ['acquire', 'visibility', 'lateLatch', 'mainEncode', 'submit']);
  assert.equal(defaultRendererWorkerProfile, 'realtime');
  assert.equal(getRendererWorkerManifest(), rendererWorkerManifests.realtime);
  assert.deepEqual([...rendererWorkerProfileNames], Object.keys(rendererWorkerManifests));
  for (const name of rendererWorkerProfileNames) {
    assert.deepEqual(getRendererWorkerProfile(name).stages, rendererWorkerManifests[name].jobs.map((j) => j.key));
    assert.equal(getRendererWorkerProfile(name), rendererWorkerProfiles[name]);
  }
});

test('every manifest is an acyclic DAG whose dependencies resolve and whose order respects them', () => {
  for (const name of rendererWorkerProfileNames) {
    const manifest = rendererWorkerManifests[name];
    const ids = manifest.jobs.map((j) => j.id);
    assert.equal(new Set(ids).size, ids.length, 'ids are unique');
    // Independent check: depth-first search finds no back edge.
    const byId = new Map(manifest.jobs.map((j) => [j.id, j]));
    const state = new Map<string, 'visiting' | 'done'>();
    const visit = (id: string): void => {
      assert.ok(byId.has(id), `dependency ${id} resolves`);
      if (state.get(id) === 'done') return;
      assert.notEqual(state.get(id), 'visiting', `cycle through ${id}`);
      state.set(id, 'visiting');
      for (const dep of byId.get(id)!.worker.dependencies) visit(dep);
      state.set(id, 'done');
    };
    ids.forEach(visit);
    // The exposed order is a permutation of the jobs where every job follows its dependencies.
    assert.deepEqual([...manifest.topologicalOrder].sort(), [...ids].sort());
    const position = new Map(manifest.topologicalOrder.map((id, i) => [id, i]));
    for (const job of manifest.jobs) {
      for (const dep of job.worker.dependencies) assert.ok(position.get(dep)! < position.get(job.id)!, `${dep} before ${job.id}`);
    }
    assert.deepEqual(manifest.roots, manifest.jobs.filter((j) => j.worker.dependencies.length === 0).map((j) => j.id));
    assert.ok(manifest.roots.length >= 2, 'multi-root DAG');
    // submit is the single sink: every job reaches it.
    const sinks = manifest.jobs.filter((j) => !manifest.jobs.some((o) => o.worker.dependencies.includes(j.id)));
    assert.deepEqual(sinks.map((j) => j.key), ['submit']);
  }
  const xr = rendererWorkerManifests.xr;
  const lateLatch = xr.jobs.find((j) => j.key === 'lateLatch')!;
  const mainEncode = xr.jobs.find((j) => j.key === 'mainEncode')!;
  assert.ok(mainEncode.worker.dependencies.includes(lateLatch.id), 'XR encodes after the pose is late-latched');
});

test('jobs carry worker, performance and debug metadata', () => {
  for (const name of rendererWorkerProfileNames) {
    for (const job of rendererWorkerManifests[name].jobs) {
      assert.equal(job.worker.queueClass, rendererWorkerQueueClass);
      assert.equal(job.worker.schedulerMode, 'dag');
      assert.equal(job.worker.jobType, `renderer.${job.key}`);
      assert.ok(Number.isFinite(job.worker.priority));
      assert.equal(job.performance.domain, 'renderer');
      assert.ok(job.performance.levels.length >= 1);
      const costs = job.performance.levels.map((l) => l.estimatedCostMs);
      assert.ok(costs.every((c, i) => c > 0 && (i === 0 || c > costs[i - 1]!)), `${job.id} levels are ordered by cost`);
      assert.equal(job.debug.owner, rendererDebugOwner);
      assert.ok(job.debug.tags.includes(name));
      assert.ok(job.debug.allocationIds.length > 0 && job.debug.allocationIds.every((a) => a.startsWith(`${rendererDebugOwner}.${name}.`)));
    }
  }
});

test('manifests and profiles are deeply immutable', () => {
  const manifest = getRendererWorkerManifest('xr');
  const job = manifest.jobs[2]!;
  assert.throws(() => {
    (manifest.jobs as RendererWorkerJob[]).push(job);
  }, TypeError);
  assert.throws(() => {
    (job.worker.dependencies as string[]).length = 0;
  }, TypeError);
  assert.throws(() => {
    (job.performance.levels[0]!.config as Record<string, unknown>).injected = 1;
  }, TypeError);
  assert.throws(() => {
    (rendererWorkerProfiles.realtime.stages as string[])[0] = 'x';
  }, TypeError);
  assert.equal(getRendererWorkerManifest('xr').jobs.length, 5);
});

test('topologicalJobOrder rejects cycles and unresolved dependencies; unknown profiles are typed errors', () => {
  const make = (id: string, deps: string[]): RendererWorkerJob => ({ id, worker: { dependencies: deps } }) as unknown as RendererWorkerJob;
  assert.throws(() => topologicalJobOrder([make('a', ['b']), make('b', ['a'])]), /cycle/);
  assert.throws(() => topologicalJobOrder([make('a', ['zzz'])]), /unknown job/);
  assert.deepEqual(topologicalJobOrder([make('c', ['a', 'b']), make('b', ['a']), make('a', [])]), ['a', 'b', 'c']);
  assert.throws(() => getRendererWorkerManifest('vr' as never), (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_OPTION' && e.field === 'profile');
});
