import type { ParsedFrameOptions } from './output-options.ts';
import type { WavefrontRenderProgress } from './output-types.ts';
import type { FrameOutcome, RendererState } from './renderer-state.ts';

/** Tells the renderer's onProgress, the frame's listener and the `progress` event listeners. */
export function emitProgress(s: RendererState, progress: WavefrontRenderProgress, listener: ((p: WavefrontRenderProgress) => void) | null): void {
  s.config.output.onProgress?.(progress);
  listener?.(progress);
  s.events.dispatchEvent(new CustomEvent('progress', { detail: progress }));
}

/** A frame's progress so far, with the remaining time extrapolated from the measured pass time. */
export function progressOf(s: RendererState, frame: ParsedFrameOptions, outcome: FrameOutcome, elapsedMs: number, done: boolean, frameNumber = s.frameCount + (done ? 0 : 1), accumulated = s.samplesAccumulated + (done ? 0 : outcome.samplesAdded)): WavefrontRenderProgress {
  const pixels = s.config.width * s.config.height;
  const counts = s.adaptive?.counts ?? null;
  let remaining = 0;
  if (!done && outcome.samplesAdded > 0) {
    const perPass = elapsedMs / outcome.samplesAdded;
    remaining = (frame.ceiling - outcome.samplesAdded) * perPass;
    if (counts && outcome.pixelSamples > 0) {
      // Adaptive frames end when every pixel converged: the predicted pixel samples at the measured rate.
      remaining = Math.min(remaining, (counts.estimatedRemainingPixelSamples * elapsedMs) / outcome.pixelSamples);
    }
    if (frame.budgetMs !== null) remaining = Math.min(remaining, Math.max(0, frame.budgetMs - elapsedMs));
  }
  return {
    frame: frameNumber,
    samplesThisFrame: outcome.samplesAdded,
    targetSamplesThisFrame: frame.ceiling,
    samplesAccumulated: accumulated,
    activePixels: counts ? counts.activePixels : pixels,
    totalPixels: pixels,
    elapsedMs,
    estimatedRemainingMs: remaining,
    estimatedTotalMs: elapsedMs + remaining,
    estimatedRemainingPixelSamples: counts ? counts.estimatedRemainingPixelSamples : null,
    done,
  };
}
