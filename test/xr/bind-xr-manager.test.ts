import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createGpuRenderer } from '../../src/runtime/create-gpu-renderer.ts';
import { bindRendererToXrManager } from '../../src/xr/bind-xr-manager.ts';
import type { XrManagerLike, XrManagerState } from '../../src/xr/xr-types.ts';
import { getRendererWorkerManifest } from '../../src/planning/worker-manifests.ts';
import { GpuRendererError } from '../../src/errors/gpu-renderer-error.ts';
import { testDevice } from '../helpers/gpu.ts';

/** A minimal store with the XR manager contract: subscribe(listener) -> unsubscribe, getState(). */
function createStore(initial: XrManagerState = { activeSession: null }) {
  let state = initial;
  const listeners = new Set<(s: XrManagerState) => void>();
  const manager: XrManagerLike & { set(s: XrManagerState): void; listenerCount(): number } = {
    subscribe(listener) {
      listeners.add(listener);
      return () => listeners.delete(listener);
    },
    getState: () => state,
    set(next) {
      state = next;
      for (const l of [...listeners]) l(state);
    },
    listenerCount: () => listeners.size,
  };
  return manager;
}

test('an active XR session switches the frame profile, frame ids and manifest; callbacks fire once per transition', async () => {
  const device = await testDevice();
  const renderer = await createGpuRenderer({
    device,
    target: { width: 1, height: 1 },
    frameIdFactory: ({ frame, xrActive }) => `scene.${xrActive ? 'xr' : 'flat'}.${frame}`,
  });
  const xr = createStore();
  const events: string[] = [];
  const session = { id: 'session-1' };
  const unbind = renderer.bindXrManager(xr, {
    onSessionStart: (e) => events.push(`start:${(e.session as { id: string }).id}`),
    onSessionEnd: (e) => events.push(`end:${(e.session as { id: string }).id}`),
  });
  assert.equal((await renderer.renderOnce()).frameId, 'scene.flat.1');

  xr.set({ activeSession: session });
  xr.set({ activeSession: session }); // repeated notification: no second start
  const snapshot = renderer.getSnapshot();
  assert.equal(snapshot.xrActive, true);
  assert.equal(snapshot.profile, 'xr');
  assert.equal(snapshot.workerManifest, getRendererWorkerManifest('xr'));
  const xrFrame = await renderer.renderOnce();
  assert.equal(xrFrame.frameId, 'scene.xr.2');
  assert.equal(xrFrame.profile, 'xr');

  xr.set({ activeSession: null });
  xr.set({});
  assert.equal(renderer.getSnapshot().xrActive, false);
  assert.equal((await renderer.renderOnce()).frameId, 'scene.flat.3');
  assert.deepEqual(events, ['start:session-1', 'end:session-1']);

  xr.set({ activeSession: session });
  assert.equal(renderer.getSnapshot().profile, 'xr');
  unbind();
  assert.equal(xr.listenerCount(), 0, 'unbinding unsubscribes');
  assert.equal(renderer.getSnapshot().xrActive, false, 'unbinding returns to realtime');
  xr.set({ activeSession: null });
  xr.set({ activeSession: { id: 'session-2' } });
  assert.deepEqual(events, ['start:session-1', 'end:session-1', 'start:session-1'], 'no callbacks after unbind');
  assert.equal(renderer.getSnapshot().xrActive, false);
  renderer.destroy();
});

test('binding to an already active manager starts immediately; rebinding replaces; destroy unbinds', async () => {
  const device = await testDevice();
  const renderer = await createGpuRenderer({ device, target: { width: 1, height: 1 } });
  const first = createStore({ activeSession: { id: 'a' } });
  let starts = 0;
  renderer.bindXrManager(first, { onSessionStart: () => starts++ });
  assert.equal(starts, 1);
  assert.equal(renderer.getSnapshot().xrActive, true);
  const second = createStore();
  renderer.bindXrManager(second);
  assert.equal(first.listenerCount(), 0, 'the previous binding is released');
  assert.equal(renderer.getSnapshot().xrActive, false);
  assert.equal(second.listenerCount(), 1);
  renderer.destroy();
  assert.equal(second.listenerCount(), 0);
});

test('bindRendererToXrManager works on any renderer with setXrActive and validates its inputs', () => {
  const calls: boolean[] = [];
  const target = { setXrActive: (active: boolean) => calls.push(active) };
  const xr = createStore();
  const unbind = bindRendererToXrManager(target, xr);
  xr.set({ activeSession: {} });
  xr.set({ activeSession: null });
  unbind();
  unbind();
  assert.deepEqual(calls, [true, false]);
  const isField = (field: string) => (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_OPTION' && e.field === field;
  assert.throws(() => bindRendererToXrManager(target, {} as never), isField('xrManager'));
  assert.throws(() => bindRendererToXrManager({} as never, xr), isField('renderer'));
  assert.throws(() => bindRendererToXrManager(target, { subscribe: () => 1, getState: () => ({}) } as never), isField('xrManager'));
  assert.throws(() => bindRendererToXrManager(target, xr, { onSessionStart: 1 as never }), isField('onSessionStart'));
});
