import { BufferUsage } from '../gpu/webgpu-constants.ts';
import { queueCounterCount } from '../gpu-layout/constants.ts';
import { createKernelBindGroups } from './bind-groups.ts';
import { waveBufferBytes } from './buffer-plan.ts';
import { DispatchTally } from './dispatch-tally.ts';
import { emitProgress, progressOf } from './frame-progress.ts';
import type { ParsedFrameOptions } from './output-options.ts';
import { writeFrameUniforms, type FrameOutcome, type RendererState } from './renderer-state.ts';
import { packBounceUniforms, packWaveUniforms } from './uniforms.ts';
import { planFrameWaves, planListWaves, type Wave } from './waves.ts';

/** Samples per adaptive-sampling step: the convergence test runs (and its count is read) between steps. */
export const adaptiveStepSamples = 4;

/**
 * Encodes waves into command buffers of at most maxFramePassesPerSubmission waves each and submits
 * them; the GPU timestamps of readback slot `slot` bracket the frame (begin at its first pass, end
 * at every batch's last, so the last write wins). Returns the number of submissions.
 */
function submitWaves(s: RendererState, waves: readonly Wave[], firstOfFrame: boolean, slot: number | null): number {
  const device = s.device;
  const perSubmission = s.config.output.maxFramePassesPerSubmission;
  let submissions = 0;
  for (let first = 0; first < waves.length; first += perSubmission) {
    const batch = waves.slice(first, first + perSubmission);
    device.queue.writeBuffer(s.resources.wave, 0, packWaveUniforms(batch));
    const encoder = device.createCommandEncoder({ label: 'wavefront frame' });
    const timestampWrites = slot === null ? undefined : s.readbacks.timestampWrites(slot, firstOfFrame && first === 0);
    const pass = encoder.beginComputePass(timestampWrites ? { timestampWrites } : {});
    s.encoderOfWaves.encode(pass, batch, s.config.maxDepth);
    pass.end();
    device.queue.submit([encoder.finish()]);
    submissions += 1;
  }
  return submissions;
}

/**
 * Grows the wave buffers (path records, queues) to hold waves of `paths` paths, up to the
 * renderer's bound, so a frame of more samples than the renderer was created with still takes
 * device-sized waves. Work already submitted keeps the old buffers until it completes.
 */
function growQueues(s: RendererState, paths: number): void {
  const wanted = Math.min(paths, s.maxWavePaths);
  if (wanted <= s.capacity) return;
  const bytes = waveBufferBytes(wanted);
  const usage = BufferUsage.STORAGE | BufferUsage.COPY_SRC | BufferUsage.COPY_DST;
  const old = { paths: s.resources.paths, queues: s.resources.queues };
  for (const name of ['paths', 'queues'] as const) {
    s.resources[name] = s.resourceMap[name] = s.buffers.create(name, bytes[name], usage, 'queue');
  }
  // The frame's statistics so far move with the queues (a frame may grow between its steps).
  const encoder = s.device.createCommandEncoder({ label: 'wave buffers' });
  encoder.copyBufferToBuffer(old.queues, 0, s.resources.queues, 0, queueCounterCount * 4);
  s.device.queue.submit([encoder.finish()]);
  s.buffers.release(old.paths);
  s.buffers.release(old.queues);
  s.capacity = wanted;
  s.encoderOfWaves.rebind(createKernelBindGroups(s.device, s.kernels, s.resourceMap));
  s.device.queue.writeBuffer(s.resources.bounce, 0, packBounceUniforms(s.config.maxDepth, s.capacity));
  writeFrameUniforms(s);
}

/** Starts a frame: zeroed statistics, a fresh dispatch tally, the denoised copy out of date. */
export function beginFrame(s: RendererState): FrameOutcome {
  const tally = new DispatchTally();
  s.encoderOfWaves.tally = tally;
  s.device.queue.writeBuffer(s.resources.queues, 0, new Uint32Array(queueCounterCount));
  s.denoisedFresh = false;
  return { samplesAdded: 0, waves: 0, wavePaths: s.capacity, submissions: 0, tally, pixelSamples: 0 };
}

/**
 * Submits `step` sample passes: full-frame waves over pixels x step samples, or list waves over
 * the pixels adaptive sampling last counted as active, then (adaptive) the convergence test, whose
 * list length comes back through the returned promise.
 */
export function submitStep(s: RendererState, outcome: FrameOutcome, step: number, slot: number | null): Promise<unknown> | null {
  const pixels = s.config.width * s.config.height;
  const adaptive = s.adaptive;
  const active = adaptive ? adaptive.counts.activePixels : pixels;
  growQueues(s, active * step);
  const waves = adaptive ? planListWaves(active, s.capacity, step) : planFrameWaves(pixels, s.capacity, s.samplesAccumulated + outcome.samplesAdded, step);
  outcome.submissions += submitWaves(s, waves, outcome.samplesAdded === 0, slot);
  outcome.waves += waves.length;
  outcome.wavePaths = s.capacity;
  outcome.samplesAdded += step;
  outcome.pixelSamples += step * active;
  if (!adaptive) return null;
  const encoder = s.device.createCommandEncoder({ label: 'adaptive sampling' });
  const staging = adaptive.encodeConvergence(encoder, outcome.tally);
  s.device.queue.submit([encoder.finish()]);
  outcome.submissions += 1;
  return adaptive.read(staging);
}

export function endFrame(s: RendererState, outcome: FrameOutcome): void {
  s.encoderOfWaves.tally = null;
  s.samplesAccumulated += outcome.samplesAdded;
  s.pixelSamplesAccumulated += outcome.pixelSamples;
  s.frameCount += 1;
}

/**
 * Submits a frame's sample passes. Without adaptive sampling or a budget: one group of waves,
 * nothing waited for. With adaptive sampling: steps of adaptiveStepSamples passes over the active
 * list, each followed by the convergence test; each step is sized by the list length of the step
 * before the previous one, so the GPU always has the next step queued while the CPU waits for a
 * count (the waves bound themselves by the GPU's own count; a pixel a stale count leaves out waits
 * a step). With a budget: the guaranteed passes, then one pass at a time while the measured pass
 * time fits (waiting for the GPU between passes).
 */
export async function renderPasses(s: RendererState, frame: ParsedFrameOptions, started: number, slot: number): Promise<FrameOutcome> {
  const outcome = beginFrame(s);
  const adaptive = s.adaptive;
  let pendingCount: Promise<unknown> | null = null;
  while (outcome.samplesAdded < frame.ceiling) {
    if (adaptive && adaptive.counts.activePixels === 0) break;
    const rendered = outcome.samplesAdded;
    let step = frame.ceiling - rendered;
    if (frame.budgetMs !== null) step = rendered < frame.minimum ? frame.minimum - rendered : 1;
    if (adaptive) step = Math.min(step, adaptiveStepSamples);
    const counted = submitStep(s, outcome, step, slot);
    const more = outcome.samplesAdded < frame.ceiling;
    if (counted) {
      if (pendingCount) await pendingCount;
      pendingCount = counted;
    } else if (more && frame.budgetMs !== null) {
      await s.device.queue.onSubmittedWorkDone();
    }
    if (!more) break;
    const elapsedMs = performance.now() - started;
    const perPassMs = elapsedMs / outcome.samplesAdded;
    if (frame.budgetMs !== null && outcome.samplesAdded >= frame.minimum && elapsedMs + perPassMs > frame.budgetMs) break;
    emitProgress(s, progressOf(s, frame, outcome, elapsedMs, false), frame.onProgress);
  }
  if (pendingCount) await pendingCount;
  endFrame(s, outcome);
  return outcome;
}

/** Denoises the accumulation into `denoised` (in `encoder`) unless it is current. */
export function encodeDenoise(s: RendererState, encoder: GPUCommandEncoder, tally: DispatchTally | null): boolean {
  if (!s.denoiser || s.denoisedFresh) return false;
  s.denoiser.encode(encoder, tally);
  s.denoisedFresh = true;
  return true;
}

/** The frame's closing submission: denoising when the canvas shows it, the statistics copy into `slot`, the present. */
export function finishFrame(s: RendererState, tally: DispatchTally, slot: number | null): boolean {
  const encoder = s.device.createCommandEncoder({ label: 'frame end' });
  const denoised = s.display.hasCanvas && s.display.source === 'denoised' ? encodeDenoise(s, encoder, tally) : false;
  if (slot !== null) s.readbacks.encodeCopy(encoder, slot, s.resources.queues);
  s.display.encodePresent(encoder);
  s.device.queue.submit([encoder.finish()]);
  return denoised;
}
