import type { BindingSpec } from '../../gpu-layout/bindings.ts';

/**
 * Bindings of the GPU BVH builder and refitter (one group; each dispatch binds the buffers its
 * program declares, so the sort's ping-pong halves and the scan's levels are the same names bound
 * to different buffers). Separate from the path tracer's table: these programs run before any
 * frame, on scratch buffers of their own, and write the `primitives`, `bvhNodes` and `bvhParents`
 * buffers the traversal later reads.
 */
export const bvhBuildBindings = {
  bvhBuild: { group: 0, binding: 0, kind: 'uniform', dynamic: true, type: 'BvhBuildUniforms', doc: 'constants of this dispatch' },
  buildPrimitives: { group: 0, binding: 1, kind: 'storage', access: 'read', type: 'array<Primitive>', doc: 'input primitives in scene order' },
  buildState: { group: 0, binding: 2, kind: 'storage', access: 'read_write', type: 'array<atomic<u32>>', doc: 'centroid bounds (order-preserving u32 encoding; minima complemented), then the Morton bit schedule' },
  sortKeysIn: { group: 0, binding: 3, kind: 'storage', access: 'read', type: 'array<u32>', doc: 'Morton keys (keyWords per primitive, low word first) read by a sort pass' },
  sortValuesIn: { group: 0, binding: 4, kind: 'storage', access: 'read', type: 'array<u32>', doc: 'scene-order primitive index of each key' },
  sortKeysOut: { group: 0, binding: 5, kind: 'storage', access: 'read_write', type: 'array<u32>', doc: 'keys written by a pass' },
  sortValuesOut: { group: 0, binding: 6, kind: 'storage', access: 'read_write', type: 'array<u32>', doc: 'values written by a pass' },
  sortHistogram: { group: 0, binding: 7, kind: 'storage', access: 'read_write', type: 'array<u32>', doc: 'digit counts per block, digit-major; scanned into scatter offsets' },
  scanData: { group: 0, binding: 8, kind: 'storage', access: 'read_write', type: 'array<u32>', doc: 'the array a scan level turns into its exclusive prefix sums' },
  scanSums: { group: 0, binding: 9, kind: 'storage', access: 'read_write', type: 'array<u32>', doc: 'block totals of a scan level (the next level scans them)' },
  gatheredPrimitives: { group: 0, binding: 10, kind: 'storage', access: 'read_write', type: 'array<Primitive>', doc: 'primitives in Morton (BVH slot) order: the renderer\'s primitives buffer' },
  sortedPrimitives: { group: 0, binding: 11, kind: 'storage', access: 'read', type: 'array<Primitive>', doc: 'the same buffer, read by the fit and the emission' },
  lbvhNodes: { group: 0, binding: 12, kind: 'storage', access: 'read_write', type: 'array<vec4u>', doc: 'LBVH interior nodes: left child, right child, first and last leaf (children: interior i < n - 1, leaf k as n - 1 + k)' },
  lbvhParents: { group: 0, binding: 13, kind: 'storage', access: 'read_write', type: 'array<u32>', doc: 'parent of every LBVH node (interior nodes, then leaves)' },
  lbvhData: { group: 0, binding: 14, kind: 'storage', access: 'read_write', type: 'array<atomic<u32>>', doc: 'per interior node: box (6 f32 bits), SAH cost, height | kept << 30 | collapsed << 31' },
  lbvhRecords: { group: 0, binding: 23, kind: 'storage', access: 'read', type: 'array<u32>', doc: 'the same words as lbvhData, read plainly once the fit and the kept marks are done' },
  lbvhFlags: { group: 0, binding: 15, kind: 'storage', access: 'read_write', type: 'array<atomic<u32>>', doc: 'children that finished each interior node (bottom-up fit)' },
  lbvhRank: { group: 0, binding: 16, kind: 'storage', access: 'read_write', type: 'array<u32>', doc: 'kept interior nodes, scanned into their rank among them' },
  outNodes: { group: 0, binding: 17, kind: 'storage', access: 'read_write', type: 'array<BvhNode>', doc: 'the finished tree: the renderer\'s bvhNodes buffer' },
  outParents: { group: 0, binding: 18, kind: 'storage', access: 'read_write', type: 'array<u32>', doc: 'parent links of the finished tree: the renderer\'s bvhParents buffer' },
  buildSummary: { group: 0, binding: 19, kind: 'storage', access: 'read_write', type: 'array<atomic<u32>>', doc: 'node count, depth, SAH cost bits, leaf count, error flags' },
  refitNodes: { group: 0, binding: 20, kind: 'storage', access: 'read_write', type: 'array<atomic<u32>>', doc: 'a finished tree (BvhNode records as words) whose boxes a refit recomputes' },
  refitParents: { group: 0, binding: 21, kind: 'storage', access: 'read', type: 'array<u32>', doc: 'its parent links' },
  refitFlags: { group: 0, binding: 22, kind: 'storage', access: 'read_write', type: 'array<atomic<u32>>', doc: 'children that finished each node (bottom-up refit)' },
} as const satisfies Record<string, BindingSpec>;

export type BvhBuildBindingName = keyof typeof bvhBuildBindings;
