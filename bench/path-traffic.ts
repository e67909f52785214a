/**
 * Bytes of path state a bounce moves through memory per path, modelled from the record members
 * each kernel reads and writes (sizes from src/gpu-layout/records.ts), for a path that hits a
 * surface, queues a shadow ray and continues (the common case), without AOVs. A model, not a
 * measurement: it leaves out the scene (BVH nodes, triangles, materials, textures), which caches
 * serve, and counts each member access once. On a GPU the measured figure would come from a
 * profiler's DRAM counters.
 *
 * The pre-fusion wavefront (five kernels per bounce, every stage handing the next a record in
 * memory) is modelled the same way for comparison, from its record sizes: ray 48, shading item
 * 48, SurfaceRecord 144, path state 64, shadow ray 48 bytes.
 */
import { fieldOf, type StructLayout } from '../src/gpu-layout/struct-layout.ts';
import { pathHitLayout, pathStateLayout, rayWorkItemLayout, sampleRecordLayout, shadowRayLayout } from '../src/gpu-layout/records.ts';

const bytes = (layout: StructLayout, ...names: string[]): number => names.reduce((n, name) => n + fieldOf(layout, name).size, 0);
/** One queue entry (a path slot). */
const ENTRY = 4;

export interface PathTraffic {
  /** Per kernel (trace: closest hit and the shadow ray; shade: material evaluation and scatter). */
  kernels: Record<string, number>;
  total: number;
}

/** The fused wavefront of this version: trace (closest hit + the previous bounce's shadow ray), shade. */
export function pathTrafficPerBounce(): PathTraffic {
  const radianceUpdate = 2 * bytes(sampleRecordLayout, 'radiance');
  const kernels = {
    'trace: closest hit': ENTRY + bytes(rayWorkItemLayout, 'origin', 'direction', 'tMax') + pathHitLayout.size + ENTRY,
    'trace: shadow ray': ENTRY + bytes(shadowRayLayout, 'origin', 'direction', 'tMax', 'contribution') + radianceUpdate,
    'shade: evaluate + scatter': ENTRY + rayWorkItemLayout.size + pathHitLayout.size + 2 * pathStateLayout.size + rayWorkItemLayout.size + ENTRY + shadowRayLayout.size + ENTRY,
  };
  return { kernels, total: Object.values(kernels).reduce((a, b) => a + b, 0) };
}

/** The five-kernel wavefront before fusion (record sizes of that version). */
export function unfusedPathTrafficPerBounce(): PathTraffic {
  const ray = 48;
  const shadingItem = 48;
  const surface = 144;
  const state = 64;
  const shadow = 48;
  const radianceUpdate = 24;
  const kernels = {
    intersect: ray + shadingItem,
    'evaluate materials': shadingItem + surface,
    scatter: surface + 2 * state + ray + shadow,
    shadow: shadow + radianceUpdate,
  };
  return { kernels, total: Object.values(kernels).reduce((a, b) => a + b, 0) };
}
