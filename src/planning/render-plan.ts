import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import { requireInteger } from '../errors/validate.ts';
import { queueCounterCount, queueCounterSlots, rendererWavefrontComputeWorkgroupSize, russianRouletteStartDepth } from '../gpu-layout/constants.ts';
import {
  bvhNodeLayout,
  materialCoreLayout,
  pathStateLayout,
  primitiveLayout,
  rayWorkItemLayout,
  rendererWavefrontAccumulationTexelBytes,
  pathHitLayout,
  pathRecordLayout,
  sampleRecordLayout,
  shadowRayLayout,
  surfaceRecordLayout,
} from '../gpu-layout/records.ts';
import { fieldOf, type StructFieldLayout, type StructLayout } from '../gpu-layout/struct-layout.ts';
import { mediumStackLimit } from '../transport/medium-stack.ts';
import { deepFreeze } from './deep-freeze.ts';
import { defaultRendererWorkerProfile, rendererWorkerQueueClass, type RendererWorkerProfileName } from './worker-constants.ts';
import { rendererWorkerProfileNames } from './worker-manifests.ts';

/**
 * The ray-tracing-first frame plan: what the frame consumes (one stable visual snapshot), the order
 * of its stages, how geometry is represented per distance band, when the acceleration structure is
 * rebuilt, and the wavefront path tracer's queue model and record contracts. The record contracts
 * are the very layout objects of src/gpu-layout/records.ts, from which the WGSL structs are
 * generated, so the plan cannot describe a layout the GPU does not use.
 */
export const rayTracingRenderPlanSchemaVersion = 1;
export const renderPlanDefaultTileSize = 256;
export const renderPlanDefaultMaxDepth = 8;
/** Upper bound on path depth (scattering vertices) for reference renders. */
export const renderPlanMaxDepthLimit = 32;

export interface RayTracingRenderPlanOptions {
  /** Identifier of the immutable visual snapshot the frame renders. */
  snapshotId: string;
  profile?: RendererWorkerProfileName;
  /** Edge of a square wavefront tile, 8..1024 (default 256): queues hold tileSize^2 paths. */
  tileSize?: number;
  /** Maximum scattering vertices per path, 1..32 (default 8). */
  maxDepth?: number;
}

export interface RenderPlanStage {
  readonly key: string;
  readonly label: string;
  readonly order: number;
  readonly dependsOn: readonly string[];
  /** Whether the stage traces rays (RT-first: visibility comes from rays, not rasterisation). */
  readonly tracesRays: boolean;
}

export interface RepresentationBand {
  readonly key: 'near' | 'mid' | 'far';
  /** Fraction of the scene radius where the band starts / ends (end of `far` is unbounded). */
  readonly startDistance: number;
  readonly endDistance: number;
  readonly geometry: 'full-triangle-mesh' | 'simplified-triangle-mesh' | 'environment';
  readonly shading: 'full-material' | 'base-material' | 'environment-radiance';
  readonly inAccelerationStructure: boolean;
}

export interface RecordContract {
  readonly name: string;
  readonly version: number;
  readonly layout: StructLayout;
  readonly bytes: number;
}

export interface RayTracingRenderPlan {
  readonly schemaVersion: number;
  readonly snapshotId: string;
  readonly profile: RendererWorkerProfileName;
  readonly inputBoundary: {
    readonly kind: 'stable-visual-snapshot';
    readonly snapshotId: string;
    /** The snapshot is read-only from `snapshotIngest` until `present` finishes. */
    readonly immutableDuringFrame: true;
    readonly consumedBy: readonly string[];
  };
  readonly renderStages: readonly RenderPlanStage[];
  readonly representationBands: readonly RepresentationBand[];
  readonly accelerationStructure: {
    readonly kind: 'binary-bvh';
    readonly nodeContract: RecordContract;
    readonly primitiveContract: RecordContract;
    readonly updatePolicy: {
      readonly trigger: 'snapshot-geometry-revision';
      readonly staticGeometry: 'build-once-reuse';
      readonly changedGeometry: 'full-rebuild';
      readonly refit: false;
    };
  };
  readonly wavefront: {
    readonly queueLayout: {
      /**
       * Each path keeps one record (state, ray, hit, shadow ray, sample) at its slot; the queues
       * hold slots. Two ray queues alternate as input and output by bounce depth.
       */
      readonly strategy: 'path-records-slot-queues';
      readonly queueClass: string;
      readonly tileSize: number;
      /** Paths per wave and entries per queue: tileSize^2, independent of the output resolution. */
      readonly capacity: number;
      readonly rayQueues: 2;
      /** Bytes of one path's whole record (PathRecord). */
      readonly pathRecordBytes: number;
      readonly rayRecordBytes: number;
      readonly hitRecordBytes: number;
      readonly surfaceRecordBytes: number;
      readonly shadowQueueCapacity: number;
      readonly shadowRecordBytes: number;
      readonly counterSlots: typeof queueCounterSlots;
      readonly counterCount: number;
      readonly workgroupSize: number;
    };
    readonly contracts: {
      /** The persistent state of a path (throughput, pixel, sample index, MIS and cone data). */
      readonly path: RecordContract;
      /** A ray waiting for closest-hit intersection. */
      readonly ray: RecordContract;
      /** What intersection hands to shading: distance, barycentrics, primitive. */
      readonly hit: RecordContract;
      readonly shadowRay: RecordContract;
      /** Material evaluation's compact per-hit BSDF parameters (in registers between the fused stages). */
      readonly surface: RecordContract;
      /** Everything the wave keeps of a path, at its slot. */
      readonly record: RecordContract;
      readonly material: RecordContract;
      /** A path sample's radiance and first-hit AOVs. */
      readonly sample: RecordContract;
      readonly medium: {
        readonly name: 'Medium';
        readonly version: number;
        readonly layout: StructLayout;
        /** The PathState field holding the nested medium stack (four 8-bit ids, innermost low). */
        readonly field: StructFieldLayout;
        readonly stackLimit: number;
      };
      readonly accumulation: { readonly name: 'Accumulation'; readonly version: 1; readonly format: 'rgba32float'; readonly bytes: number };
    };
    readonly termination: {
      /** Radiance is committed when a path hits an emitter or escapes to the environment. */
      readonly completion: readonly ['emissive', 'environment'];
      /** Emitter/environment hits after a BSDF sample are weighted against light sampling. */
      readonly multipleImportanceSampling: 'power-heuristic';
      readonly russianRoulette: {
        /** Roulette applies once the path depth is at least this (pbrt-v4 applies it from depth 1). */
        readonly startDepth: number;
        /** q = min(1, max component of throughput * etaScale); survivors are divided by q. */
        readonly survivalProbability: 'min(1, maxComponent(throughput * etaScale))';
      };
      readonly maxDepth: number;
      readonly maxDepthLimit: number;
    };
  };
}

const contract = (layout: StructLayout): RecordContract => ({ name: layout.name, version: layout.version, layout, bytes: layout.size });

const stages: readonly Omit<RenderPlanStage, 'order'>[] = [
  { key: 'snapshotIngest', label: 'Ingest the stable visual snapshot', dependsOn: [], tracesRays: false },
  { key: 'accelerationUpdate', label: 'Update the acceleration structure', dependsOn: ['snapshotIngest'], tracesRays: false },
  { key: 'primaryRays', label: 'Generate camera rays per tile', dependsOn: ['accelerationUpdate'], tracesRays: true },
  { key: 'intersect', label: 'Trace closest hits, sorting paths into hit and escaped queues', dependsOn: ['primaryRays'], tracesRays: true },
  { key: 'escaped', label: 'Add environment radiance to escaped paths', dependsOn: ['intersect'], tracesRays: false },
  { key: 'materialEvaluation', label: 'Evaluate materials: geometry, textures, normal maps into BSDF parameters', dependsOn: ['intersect'], tracesRays: false },
  { key: 'scatter', label: 'Sample lights and the BSDF, play Russian roulette, queue continuations', dependsOn: ['materialEvaluation'], tracesRays: false },
  { key: 'shadowRays', label: 'Trace next-event-estimation shadow rays', dependsOn: ['scatter'], tracesRays: true },
  { key: 'accumulate', label: 'Accumulate radiance and AOVs', dependsOn: ['escaped', 'shadowRays'], tracesRays: false },
  { key: 'resolve', label: 'Tone map and present', dependsOn: ['accumulate'], tracesRays: false },
];

export function createRayTracingRenderPlan(options: RayTracingRenderPlanOptions): RayTracingRenderPlan {
  if (typeof options !== 'object' || options === null) throw new GpuRendererError('INVALID_OPTION', 'expected an options object', { field: 'options' });
  const { snapshotId } = options;
  if (typeof snapshotId !== 'string' || snapshotId.length === 0) {
    throw new GpuRendererError('INVALID_OPTION', 'expected a non-empty snapshot id string', { field: 'snapshotId' });
  }
  const profile = options.profile ?? defaultRendererWorkerProfile;
  if (!(rendererWorkerProfileNames as readonly string[]).includes(profile)) {
    throw new GpuRendererError('INVALID_OPTION', `unknown profile ${JSON.stringify(profile)}`, { field: 'profile' });
  }
  const tileSize = requireInteger(options.tileSize ?? renderPlanDefaultTileSize, 'tileSize', { min: 8, max: 1024 });
  const maxDepth = requireInteger(options.maxDepth ?? renderPlanDefaultMaxDepth, 'maxDepth', { min: 1, max: renderPlanMaxDepthLimit });
  const capacity = tileSize * tileSize;

  const plan: RayTracingRenderPlan = {
    schemaVersion: rayTracingRenderPlanSchemaVersion,
    snapshotId,
    profile,
    inputBoundary: {
      kind: 'stable-visual-snapshot',
      snapshotId,
      immutableDuringFrame: true,
      consumedBy: ['snapshotIngest', 'accelerationUpdate'],
    },
    renderStages: stages.map((stage, order) => ({ ...stage, order })),
    representationBands: [
      { key: 'near', startDistance: 0, endDistance: 0.25, geometry: 'full-triangle-mesh', shading: 'full-material', inAccelerationStructure: true },
      { key: 'mid', startDistance: 0.25, endDistance: 1, geometry: 'simplified-triangle-mesh', shading: 'base-material', inAccelerationStructure: true },
      { key: 'far', startDistance: 1, endDistance: Infinity, geometry: 'environment', shading: 'environment-radiance', inAccelerationStructure: false },
    ],
    accelerationStructure: {
      kind: 'binary-bvh',
      nodeContract: contract(bvhNodeLayout),
      primitiveContract: contract(primitiveLayout),
      updatePolicy: { trigger: 'snapshot-geometry-revision', staticGeometry: 'build-once-reuse', changedGeometry: 'full-rebuild', refit: false },
    },
    wavefront: {
      queueLayout: {
        strategy: 'path-records-slot-queues',
        queueClass: rendererWorkerQueueClass,
        tileSize,
        capacity,
        rayQueues: 2,
        pathRecordBytes: pathRecordLayout.size,
        rayRecordBytes: rayWorkItemLayout.size,
        hitRecordBytes: pathHitLayout.size,
        surfaceRecordBytes: surfaceRecordLayout.size,
        // At most one shadow ray per path per bounce.
        shadowQueueCapacity: capacity,
        shadowRecordBytes: shadowRayLayout.size,
        // A copy: freezing the plan must not freeze records.ts's own object.
        counterSlots: { ...queueCounterSlots },
        counterCount: queueCounterCount,
        workgroupSize: rendererWavefrontComputeWorkgroupSize,
      },
      contracts: {
        path: contract(pathStateLayout),
        ray: contract(rayWorkItemLayout),
        hit: contract(pathHitLayout),
        shadowRay: contract(shadowRayLayout),
        surface: contract(surfaceRecordLayout),
        record: contract(pathRecordLayout),
        material: contract(materialCoreLayout),
        sample: contract(sampleRecordLayout),
        medium: { name: 'Medium', version: pathStateLayout.version, layout: pathStateLayout, field: fieldOf(pathStateLayout, 'media'), stackLimit: mediumStackLimit },
        accumulation: { name: 'Accumulation', version: 1, format: 'rgba32float', bytes: rendererWavefrontAccumulationTexelBytes },
      },
      termination: {
        completion: ['emissive', 'environment'],
        multipleImportanceSampling: 'power-heuristic',
        russianRoulette: { startDepth: russianRouletteStartDepth, survivalProbability: 'min(1, maxComponent(throughput * etaScale))' },
        maxDepth,
        maxDepthLimit: renderPlanMaxDepthLimit,
      },
    },
  };
  return deepFreeze(plan);
}
