import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import type { AdaptiveScheduler } from '../film/adaptive/scheduler.ts';
import type { InstanceIds } from '../film/accumulation/readback.ts';
import type { WavefrontDenoiser } from '../film/denoise/denoiser.ts';
import type { FilmDisplay } from '../film/display/film-display.ts';
import type { GpuLighting } from '../lighting/gpu-lighting.ts';
import type { NormalizedScene } from '../scene/normalize-scene.ts';
import type { PathTracerResourceMap } from './bind-groups.ts';
import type { DispatchTally } from './dispatch-tally.ts';
import type { PlannedBufferName } from './buffer-plan.ts';
import type { WavefrontPathTracingComputeConfig } from './config.ts';
import type { WavefrontEncoder } from './frame-encoder.ts';
import type { FrameReadbackRing } from './frame-stats.ts';
import type { GpuBufferSet } from './gpu-buffers.ts';
import type { PathTracerPipelines } from './pipelines.ts';
import type { SceneAcceleration } from './scene/scene-acceleration.ts';
import type { PreparedScene } from './scene/prepare-scene.ts';
import type { SceneSources } from './scene-update.ts';
import type { SubmissionQueue } from './submission-queue.ts';
import { packFrameUniforms } from './uniforms.ts';

/**
 * What one renderer's parts share: the device, its configuration, the uploaded scene, the buffers
 * and the accumulation's progress. The renderer (renderer.ts) owns it; the frame passes, the
 * readbacks and the updates each read and change it.
 */
export interface RendererState {
  readonly device: GPUDevice;
  /** Where progress events are dispatched (the renderer itself). */
  readonly events: EventTarget;
  config: WavefrontPathTracingComputeConfig;
  scene: { instanceCount: number; sceneObjectCount: number; prepared: PreparedScene; normalized: NormalizedScene };
  /** What updateScene rebuilds geometry from: the packed materials, the compiled features, the lighting options. */
  sources: SceneSources;
  readonly kernels: PathTracerPipelines['kernels'];
  /** The BVH on the device (build mode, refit and rebuild for geometry updates). */
  acceleration: SceneAcceleration | null;
  /** Paths per wave the queue buffers hold now, and the most they may grow to. */
  capacity: number;
  readonly maxWavePaths: number;
  readonly buffers: GpuBufferSet;
  readonly resources: Record<PlannedBufferName, GPUBuffer>;
  readonly resourceMap: PathTracerResourceMap;
  lighting: GpuLighting;
  readonly textureBytes: number;
  readonly encoderOfWaves: WavefrontEncoder;
  readonly display: FilmDisplay;
  readonly readbacks: FrameReadbackRing;
  /** Submission phases of renderFrame / renderOnce calls run one at a time, in call order. */
  readonly submissions: SubmissionQueue;
  readonly adaptive: AdaptiveScheduler | null;
  readonly denoiser: WavefrontDenoiser | null;
  instanceIds: InstanceIds;
  frameCount: number;
  samplesAccumulated: number;
  /** Pixel samples in the accumulation (differs from pixels x samplesAccumulated with adaptive sampling). */
  pixelSamplesAccumulated: number;
  /** Whether `denoised` holds the denoiser's output for the current accumulation. */
  denoisedFresh: boolean;
  destroyed: boolean;
  deviceLost: boolean;
  deviceLostMessage: string;
}

/** What one frame's passes produced, before the statistics are read back. */
export interface FrameOutcome {
  samplesAdded: number;
  waves: number;
  /** Paths per wave when the frame's last wave was encoded. */
  wavePaths: number;
  submissions: number;
  tally: DispatchTally;
  pixelSamples: number;
}

export function assertUsable(s: RendererState): void {
  if (s.destroyed) throw new GpuRendererError('RENDERER_DESTROYED', 'the renderer has been destroyed');
  if (s.deviceLost) throw new GpuRendererError('DEVICE_LOST', `the GPU device was lost: ${s.deviceLostMessage}`);
}

/** Waits until every frame requested so far has been submitted, so a read sees all of them. */
export async function submittedWork(s: RendererState): Promise<void> {
  assertUsable(s);
  await s.submissions.after(() => undefined);
  assertUsable(s);
}

export function writeFrameUniforms(s: RendererState): void {
  const p = s.scene.prepared;
  s.device.queue.writeBuffer(
    s.resources.frame,
    0,
    packFrameUniforms(s.config, {
      lightCount: s.lighting.boundedCount,
      environmentSelectProbability: s.lighting.environmentSelectProbability,
      environmentRadiance: s.lighting.uniformEnvironment,
      sceneCenter: p.sceneCenter,
      sceneRadius: p.sceneRadius,
      queueCapacity: s.capacity,
    }),
  );
}

/** Clears the film and restarts the accumulation (after a camera or scene change). */
export function resetAccumulation(s: RendererState): void {
  const encoder = s.device.createCommandEncoder();
  encoder.clearBuffer(s.resources.film);
  encoder.clearBuffer(s.resources.filmAovs);
  encoder.clearBuffer(s.resources.filmMoments);
  encoder.clearBuffer(s.resources.filmIds);
  s.device.queue.submit([encoder.finish()]);
  s.adaptive?.reset();
  s.samplesAccumulated = 0;
  s.pixelSamplesAccumulated = 0;
  s.denoisedFresh = false;
  s.frameCount = 0;
}
