/**
 * The BVH worker's message loop. Like `createBvhKernels` it is self-contained (it uses nothing but its
 * arguments and globals): the inline worker's source is the text of both functions (see
 * bvh-worker-pool.ts), so it runs unchanged from the .ts sources, dist/esm, dist/cjs or a bundle.
 *
 * Requests carry an `id` that the reply echoes. Ops:
 * - `begin`: the shared slot buffers (SharedArrayBuffer views) and settings of build `build`;
 * - `boxes`: triangle AABBs of [from, to) (the prepass), replying their bounds;
 * - `split`: one node split (`mid` = -1 for a leaf), replying the children's bounds;
 * - `subtree`: a whole subtree in depth-first order into a fresh node buffer (transferred back);
 *   it stops early, replying `aborted`, once the build's shared abort flag is set;
 * - `end`: forget build `build`;
 * - `full`: the whole single-threaded build of copied positions (no shared memory needed).
 */
import type { BvhBuildParams, BvhKernels, SlotBuffers } from './bvh-kernels.ts';

/** What the worker needs from its host: Node's `parentPort` or a browser worker's global scope. */
export interface BvhWorkerHost {
  onMessage(handler: (message: unknown) => void): void;
  post(message: unknown, transfer: Transferable[]): void;
}

export interface WorkerBuildMessage {
  op: string;
  id: number;
  build: number;
  [key: string]: unknown;
}

export function bvhWorkerMain(createKernels: () => BvhKernels, host: BvhWorkerHost): void {
  const k = createKernels();
  interface Build {
    slots: SlotBuffers;
    positions: Float32Array;
    params: BvhBuildParams;
    abort: Int32Array;
    split: ReturnType<BvhKernels['createSplitter']>;
  }
  const builds = new Map<number, Build>();
  // How long a subtree build runs between two looks at the abort flag.
  const ABORT_POLL_MS = 4;

  const handle = (m: WorkerBuildMessage): { reply: Record<string, unknown>; transfer: Transferable[] } => {
    if (m.op === 'begin') {
      const params = m.params as BvhBuildParams;
      builds.set(m.build, {
        slots: { boxes0: m.boxes0 as Float32Array, ids0: m.ids0 as Uint32Array, boxes1: m.boxes1 as Float32Array, ids1: m.ids1 as Uint32Array },
        positions: m.positions as Float32Array,
        params,
        abort: m.abort as Int32Array,
        split: k.createSplitter(params),
      });
      return { reply: {}, transfer: [] };
    }
    if (m.op === 'end') {
      builds.delete(m.build);
      return { reply: {}, transfer: [] };
    }
    if (m.op === 'full') {
      const positions = m.positions as Float32Array;
      const params = m.params as BvhBuildParams;
      const n = positions.length / 9;
      const slots = { boxes0: new Float32Array(n * 6), ids0: new Uint32Array(n), boxes1: new Float32Array(n * 6), ids1: new Uint32Array(n) };
      const rootBounds = new Float64Array(12);
      k.emptyBounds(rootBounds, 0);
      k.computeBoxes(positions, slots.boxes0, slots.ids0, 0, n, rootBounds, 0);
      const nodes = new ArrayBuffer(Math.max(1, 2 * n - 1) * 32);
      const b = k.createSubtreeBuild({ ...slots, count: n, slotBase: 0, depth: 0, rootBounds, nodes, params });
      b.step(Infinity);
      const exact = nodes.slice(0, b.nodeCount() * 32);
      return {
        reply: { nodes: exact, nodeCount: b.nodeCount(), leafCount: b.leafCount(), depth: b.depthReached(), order: slots.ids0 },
        transfer: [exact, slots.ids0.buffer],
      };
    }
    const build = builds.get(m.build);
    if (!build) throw new Error(`bvh worker: unknown build ${m.build}`);
    if (m.op === 'boxes') {
      const bounds = new Float64Array(12);
      k.emptyBounds(bounds, 0);
      k.computeBoxes(build.positions, build.slots.boxes0, build.slots.ids0, m.from as number, m.to as number, bounds, 0);
      return { reply: { bounds }, transfer: [] };
    }
    const start = m.start as number;
    const count = m.count as number;
    const depth = m.depth as number;
    const bounds = m.bounds as Float64Array;
    if (m.op === 'split') {
      const out = new Float64Array(24);
      const mid = build.split(build.slots, start, count, depth, bounds, 0, bounds, 6, out);
      if (mid < 0) k.settleLeaf(build.slots, start, count, depth);
      return { reply: { mid, out }, transfer: [] };
    }
    if (m.op === 'subtree') {
      const s = build.slots;
      const nodes = new ArrayBuffer((2 * count - 1) * 32);
      const b = k.createSubtreeBuild({
        boxes0: s.boxes0.subarray(start * 6, (start + count) * 6),
        ids0: s.ids0.subarray(start, start + count),
        boxes1: s.boxes1.subarray(start * 6, (start + count) * 6),
        ids1: s.ids1.subarray(start, start + count),
        count,
        slotBase: start,
        depth,
        rootBounds: bounds,
        nodes,
        params: build.params,
      });
      for (;;) {
        if (Atomics.load(build.abort, 0) !== 0) return { reply: { aborted: true }, transfer: [] };
        if (b.step(performance.now() + ABORT_POLL_MS)) break;
      }
      return {
        reply: { nodes, nodeCount: b.nodeCount(), leafCount: b.leafCount(), depth: b.depthReached() },
        transfer: [nodes],
      };
    }
    throw new Error(`bvh worker: unknown op ${m.op}`);
  };

  host.onMessage((data) => {
    const m = data as WorkerBuildMessage;
    try {
      const { reply, transfer } = handle(m);
      reply.id = m.id;
      host.post(reply, transfer);
    } catch (error) {
      host.post({ id: m.id, error: error instanceof Error ? `${error.message}\n${error.stack ?? ''}` : String(error) }, []);
    }
  });
}
