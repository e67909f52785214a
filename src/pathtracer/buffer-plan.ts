import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import { adaptiveListSlots, dynamicUniformStride, indirectDispatchBytes, queueBufferWords } from '../gpu-layout/constants.ts';
import {
  alphaPrimitiveLayout,
  bvhNodeLayout,
  frameUniformsLayout,
  instanceLayout,
  lightingUniformsLayout,
  lightRecordLayout,
  pathRecordLayout,
  primitiveLayout,
  resolveUniformsLayout,
  adaptiveUniformsLayout,
  denoiseUniformsLayout,
  denoiseGuideLayout,
  filmAovPixelLayout,
  filmMomentsLayout,
  filmPixelLayout,
} from '../gpu-layout/records.ts';
import type { PathTracerBindingName } from '../gpu-layout/bindings.ts';

/** Which memory statistic a buffer counts towards. */
export type BufferCategory = 'scene' | 'queue' | 'frame';

export interface PlannedBuffer {
  bytes: number;
  category: BufferCategory;
  /** The input responsible for its size (named in SCENE_TOO_LARGE errors). */
  field: string;
  /** What it holds, for error messages. */
  what: string;
}

/** Buffers of the path tracer that are not bindings of its kernels. */
export type AuxiliaryBufferName = 'displayUniforms' | 'displayPixels' | 'timestamps';

export type PlannedBufferName = Exclude<PathTracerBindingName, 'textureAtlas' | 'environmentTexture'> | AuxiliaryBufferName;

/** Sizes the plan is computed from: known before the BVH is built or anything is allocated. */
export interface BufferPlanInput {
  width: number;
  height: number;
  /** Paths per wave (wave-capacity.ts): what the queue buffers hold. */
  wavePaths: number;
  maxDepth: number;
  aovs: boolean;
  /** Output features that size full-frame buffers; all false keeps them minimal. */
  output?: { moments: boolean; adaptive: boolean; denoise: boolean; atrous?: boolean };
  /** Frames whose statistics may be in flight at once (one timestamp pair each); default 1. */
  framesInFlight?: number;
  /** Waves encoded per command buffer (maxFramePassesPerSubmission); default maxWavesPerSubmission. */
  wavesPerSubmission?: number;
  /** Bytes of the vertex streams and of the index buffer (pack-vertices.ts vertexStreamBytes). */
  vertexStreams: number;
  indices: number;
  /** Primitive records: the top level's (flattened triangles, placements, analytic shapes) and the bottom levels' triangles. */
  primitiveCount: number;
  /** Upper bound of BVH nodes over every level (default 2 primitiveCount - 1). */
  bvhNodeCount?: number;
  /** What the primitive records hold, named when they do not fit. */
  geometry?: string;
  alphaPrimitiveCount: number;
  instanceCount: number;
  lightCount: number;
  /** Vec4 cells of the lights heap when known (src/lighting/gpu-lighting.ts); else estimated from lightCount. */
  lightHeapCells?: number;
  /** Vec4 cells of the material heap. */
  materialCells: number;
}

/** Bytes of the wave buffers (path records; statistics and queues) for waves of `wavePaths` paths. */
export function waveBufferBytes(wavePaths: number): { paths: number; queues: number } {
  return { paths: wavePaths * pathRecordLayout.size, queues: queueBufferWords(wavePaths) * 4 };
}

/** Byte size of every buffer a render needs, computed before anything is allocated. */
export function planBuffers(i: BufferPlanInput): Record<PlannedBufferName, PlannedBuffer> {
  const capacity = i.wavePaths;
  const pixels = i.width * i.height;
  const n = Math.max(1, i.primitiveCount);
  const nodes = Math.max(1, i.bvhNodeCount ?? 2 * n - 1);
  const scene = (bytes: number, what: string, field = 'meshes'): PlannedBuffer => ({ bytes, category: 'scene', field, what });
  const queue = (bytes: number, what: string): PlannedBuffer => ({ bytes, category: 'queue', field: 'tileSize', what });
  const frame = (bytes: number, what: string): PlannedBuffer => ({ bytes, category: 'frame', field: 'width', what });
  const out = i.output ?? { moments: false, adaptive: false, denoise: false };
  const perPixel = (on: boolean, count = 1): number => (on ? pixels * count : 1);
  return {
    primitives: scene(n * primitiveLayout.size, `the primitive buffer (${n} records${i.geometry ? `: ${i.geometry}` : ''})`),
    // A binary BVH over n primitives has at most 2n - 1 nodes (per level, with two levels).
    bvhNodes: scene(nodes * bvhNodeLayout.size, `the BVH node buffer (${nodes} nodes)`),
    bvhParents: scene(nodes * 4, 'the BVH parent links'),
    alphaPrimitives: scene(Math.max(1, i.alphaPrimitiveCount) * alphaPrimitiveLayout.size, 'the alpha-test records'),
    instances: scene(Math.max(1, i.instanceCount) * instanceLayout.size, 'the instance buffer', 'instances'),
    indices: scene(i.indices, 'the index buffer'),
    vertexStreams: scene(i.vertexStreams, 'the vertex streams'),
    materials: scene(Math.max(1, i.materialCells) * 16, 'the material heap', 'materials'),
    lights: scene(i.lightHeapCells !== undefined ? Math.max(1, i.lightHeapCells) * 16 : Math.max(1, i.lightCount) * lightRecordLayout.size, 'the lights heap'),
    lighting: frame(lightingUniformsLayout.size, 'the lighting constants'),
    frame: frame(frameUniformsLayout.size, 'the frame constants'),
    paths: queue(waveBufferBytes(capacity).paths, 'the path records'),
    queues: queue(waveBufferBytes(capacity).queues, 'the statistics and queues'),
    wave: queue((i.wavesPerSubmission ?? maxWavesPerSubmission) * dynamicUniformStride, 'the wave constants'),
    bounce: queue((i.maxDepth + 1) * dynamicUniformStride, 'the bounce constants'),
    shadingDispatch: queue((i.maxDepth + 1) * indirectDispatchBytes, 'the shading dispatch sizes'),
    film: frame(pixels * filmPixelLayout.size, 'the accumulation buffer (width x height)'),
    filmAovs: frame(perPixel(i.aovs) * filmAovPixelLayout.size, 'the AOV accumulation (width x height)'),
    filmMoments: frame(perPixel(out.moments) * filmMomentsLayout.size, 'the film moments (width x height)'),
    filmIds: frame(perPixel(i.aovs) * 4, 'the id AOV (width x height)'),
    adaptive: frame(adaptiveUniformsLayout.size, 'the adaptive-sampling constants'),
    adaptiveError: frame(perPixel(out.adaptive) * 4, 'the adaptive-sampling errors (width x height)'),
    adaptivePixels: frame((adaptiveListSlots.listStart + (out.adaptive ? pixels : 0)) * 4, 'the active-pixel list (width x height)'),
    denoise: frame(denoiseUniformsLayout.size, 'the denoiser input constants'),
    denoiseColor: frame(perPixel(out.atrous ?? out.denoise, 2) * 16, 'the a-trous ping-pong buffers (width x height)'),
    denoiseGuide: frame(perPixel(out.atrous ?? out.denoise) * denoiseGuideLayout.size, 'the a-trous guides (width x height)'),
    denoised: frame(perPixel(out.denoise) * 16, 'the denoised image (width x height)'),
    denoiseEnergy: frame((out.atrous ?? out.denoise ? 1 + 2 * Math.ceil(i.width / 8) * Math.ceil(i.height / 8) : 1) * 16, 'the a-trous energy sums (width x height / 64)'),
    displayUniforms: frame(resolveUniformsLayout.size, 'the display constants'),
    displayPixels: frame(pixels * 4, 'the display pixels (width x height)'),
    timestamps: frame(256 * (i.framesInFlight ?? 1), 'the timestamp results'),
  };
}

/** Most waves (tile x sample) encoded into one command buffer, bounding submission size. */
export const maxWavesPerSubmission = 16;

/**
 * Rejects, before any allocation, a scene or frame whose buffers exceed what one binding of this
 * device holds, naming the input responsible. (Scenes are refused, never truncated.)
 */
export function checkBufferLimits(limits: GPUSupportedLimits, plan: Record<string, PlannedBuffer>): void {
  const max = Math.min(limits.maxStorageBufferBindingSize, limits.maxBufferSize);
  for (const b of Object.values(plan)) {
    if (b.bytes > max) {
      throw new GpuRendererError('SCENE_TOO_LARGE', `${b.what} needs ${b.bytes} bytes but this device binds at most ${max} bytes per storage buffer (${b.bytes - max} bytes, ${(b.bytes / max).toFixed(2)}x, too many)`, { field: b.field });
    }
  }
}
