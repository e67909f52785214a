import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import { deepFreeze } from './deep-freeze.ts';
import { topologicalJobOrder } from './validate-manifest.ts';
import {
  defaultRendererWorkerProfile,
  rendererDebugOwner,
  rendererWorkerQueueClass,
  type RendererWorkerProfileName,
} from './worker-constants.ts';
import type {
  RendererJobAuthority,
  RendererJobBudgetLevel,
  RendererJobImportance,
  RendererWorkerJob,
  RendererWorkerManifest,
  RendererWorkerProfile,
} from './worker-manifest-types.ts';

/**
 * The renderer's frame stages as worker jobs (docs: "Worker DAG Manifests"). `acquire` (take the
 * frame's target texture and the stable visual snapshot) and `visibility` (cull against that
 * snapshot) are independent roots, so schedulers can overlap them; encoding waits for both.
 * In XR, `lateLatch` re-reads the viewer pose as late as possible after the frame is acquired
 * (WebXR `XRFrame.getViewerPose`, valid only inside the frame callback) before encoding.
 */
interface JobSpec {
  key: string;
  label: string;
  priority: number;
  dependsOn: readonly string[];
  authority: RendererJobAuthority;
  importance: RendererJobImportance;
  levels: readonly RendererJobBudgetLevel[];
  tags: readonly string[];
  allocations: readonly string[];
}

const fixedLevel = (costMs: number): readonly RendererJobBudgetLevel[] => [{ id: 'fixed', estimatedCostMs: costMs, config: {} }];

const jobSpecs: Record<string, JobSpec> = {
  acquire: {
    key: 'acquire',
    label: 'Acquire frame target and visual snapshot',
    priority: 100,
    dependsOn: [],
    authority: 'presentation',
    importance: 'critical',
    levels: fixedLevel(0.1),
    tags: ['frame', 'swapchain'],
    allocations: ['frame-target'],
  },
  visibility: {
    key: 'visibility',
    label: 'Visibility and culling',
    priority: 80,
    dependsOn: [],
    authority: 'visual',
    importance: 'high',
    levels: [
      { id: 'coarse', estimatedCostMs: 0.3, config: { cullingGranularity: 'object', occlusionCulling: false } },
      { id: 'standard', estimatedCostMs: 0.6, config: { cullingGranularity: 'object', occlusionCulling: true } },
      { id: 'fine', estimatedCostMs: 1.0, config: { cullingGranularity: 'cluster', occlusionCulling: true } },
    ],
    tags: ['culling'],
    allocations: ['visibility-list'],
  },
  lateLatch: {
    key: 'lateLatch',
    label: 'Late-latch XR viewer pose',
    priority: 95,
    dependsOn: ['acquire'],
    authority: 'presentation',
    importance: 'critical',
    levels: fixedLevel(0.05),
    tags: ['xr', 'pose'],
    allocations: ['xr-view-uniforms'],
  },
  mainEncode: {
    key: 'mainEncode',
    label: 'Encode main pass',
    priority: 90,
    dependsOn: ['acquire', 'visibility'],
    authority: 'visual',
    importance: 'critical',
    levels: [
      { id: 'low', estimatedCostMs: 2, config: { renderScale: 0.5, samplesPerPixel: 1 } },
      { id: 'medium', estimatedCostMs: 4, config: { renderScale: 0.75, samplesPerPixel: 1 } },
      { id: 'high', estimatedCostMs: 7, config: { renderScale: 1, samplesPerPixel: 1 } },
      { id: 'ultra', estimatedCostMs: 12, config: { renderScale: 1, samplesPerPixel: 2 } },
    ],
    tags: ['encode', 'main-pass'],
    allocations: ['command-encoder', 'main-pass'],
  },
  postProcess: {
    key: 'postProcess',
    label: 'Post-process and tone map',
    priority: 60,
    dependsOn: ['mainEncode'],
    authority: 'visual',
    importance: 'medium',
    levels: [
      { id: 'minimal', estimatedCostMs: 0.3, config: { toneMapping: true, denoise: false } },
      { id: 'full', estimatedCostMs: 1.5, config: { toneMapping: true, denoise: true } },
    ],
    tags: ['post'],
    allocations: ['post-targets'],
  },
  submit: {
    key: 'submit',
    label: 'Submit and present',
    priority: 100,
    dependsOn: ['postProcess'],
    authority: 'presentation',
    importance: 'critical',
    levels: fixedLevel(0.1),
    tags: ['frame', 'submit'],
    allocations: ['command-buffer'],
  },
};

/** Stage keys per profile, with per-profile dependency overrides where a profile lacks a stage. */
const profileSpecs: Record<RendererWorkerProfileName, { label: string; description: string; stages: readonly string[]; overrides: Record<string, readonly string[]> }> = {
  realtime: {
    label: 'Realtime',
    description: 'Flat-screen frame: acquire and visibility in parallel, encode, post-process, submit.',
    stages: ['acquire', 'visibility', 'mainEncode', 'postProcess', 'submit'],
    overrides: {},
  },
  xr: {
    label: 'XR',
    description: 'Immersive frame: the viewer pose is late-latched after acquire; no separate post pass to keep motion-to-photon latency low.',
    stages: ['acquire', 'visibility', 'lateLatch', 'mainEncode', 'submit'],
    overrides: { mainEncode: ['visibility', 'lateLatch'], submit: ['mainEncode'] },
  },
};

export const rendererWorkerProfileNames: readonly RendererWorkerProfileName[] = Object.freeze(['realtime', 'xr'] as RendererWorkerProfileName[]);

const jobId = (profile: string, key: string): string => `renderer.${profile}.${key}`;

function buildManifest(profile: RendererWorkerProfileName): RendererWorkerManifest {
  const spec = profileSpecs[profile];
  const jobs: RendererWorkerJob[] = spec.stages.map((key) => {
    const job = jobSpecs[key]!;
    const id = jobId(profile, key);
    return {
      id,
      key,
      label: job.label,
      worker: {
        jobType: `renderer.${key}`,
        queueClass: rendererWorkerQueueClass,
        priority: job.priority,
        dependencies: (spec.overrides[key] ?? job.dependsOn).map((dep) => jobId(profile, dep)),
        schedulerMode: 'dag',
      },
      performance: {
        id: `${id}.budget`,
        domain: 'renderer',
        authority: job.authority,
        importance: job.importance,
        levels: job.levels.map((level) => ({ ...level, config: { ...level.config } })),
      },
      debug: {
        owner: rendererDebugOwner,
        tags: [rendererDebugOwner, profile, ...job.tags],
        allocationIds: job.allocations.map((a) => `${rendererDebugOwner}.${profile}.${a}`),
      },
    };
  });
  const topologicalOrder = topologicalJobOrder(jobs);
  return deepFreeze({
    schemaVersion: 1,
    profile,
    owner: rendererDebugOwner,
    queueClass: rendererWorkerQueueClass,
    schedulerMode: 'dag',
    jobs,
    roots: jobs.filter((j) => j.worker.dependencies.length === 0).map((j) => j.id),
    topologicalOrder,
  });
}

export const rendererWorkerManifests: Readonly<Record<RendererWorkerProfileName, RendererWorkerManifest>> = Object.freeze({
  realtime: buildManifest('realtime'),
  xr: buildManifest('xr'),
});

export const rendererWorkerProfiles: Readonly<Record<RendererWorkerProfileName, RendererWorkerProfile>> = deepFreeze({
  realtime: { name: 'realtime', label: profileSpecs.realtime.label, description: profileSpecs.realtime.description, stages: [...profileSpecs.realtime.stages] },
  xr: { name: 'xr', label: profileSpecs.xr.label, description: profileSpecs.xr.description, stages: [...profileSpecs.xr.stages] },
});

function resolveProfileName(name: unknown): RendererWorkerProfileName {
  if (name === undefined) return defaultRendererWorkerProfile;
  if (typeof name === 'string' && (rendererWorkerProfileNames as readonly string[]).includes(name)) return name as RendererWorkerProfileName;
  throw new GpuRendererError('INVALID_OPTION', `unknown renderer worker profile ${JSON.stringify(name)}; expected one of ${rendererWorkerProfileNames.join(', ')}`, {
    field: 'profile',
  });
}

export function getRendererWorkerProfile(name?: RendererWorkerProfileName): RendererWorkerProfile {
  return rendererWorkerProfiles[resolveProfileName(name)];
}

export function getRendererWorkerManifest(name?: RendererWorkerProfileName): RendererWorkerManifest {
  return rendererWorkerManifests[resolveProfileName(name)];
}
