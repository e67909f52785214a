/**
 * `render` with --frames, --turntable, --variants or --cameras: plans the sequence, skips frames whose file
 * exists (unless --overwrite), poses each remaining frame from the asset loaded once, renders it
 * with one path tracer updated in place, and writes it atomically. One progress bar covers the
 * whole sequence, with the current frame's and the sequence's time left.
 */
import type { GltfScene } from '../io/gltf/gltf-scene-reader.ts';
import { planGltfSequence, poseGltfSequenceItem, sequencePatternValues, type GltfSequenceItem } from '../sequence/gltf-sequence.ts';
import { frameFileExists, writeFrameFile } from '../io/frame-files.ts';
import { outputPaths } from '../sequence/output-pattern.ts';
import { createSequenceRenderer } from '../sequence/sequence-renderer.ts';
import type { RenderCommand } from './args.ts';
import { applyCameraFlags } from './camera-flags.ts';
import { applyCliLighting } from './scene-lighting.ts';
import { createProgressBar, formatDuration, type ProgressStream } from './progress.ts';
import { accumulateImage, commandResourcePolicy, encodeOutput, loadGltfForCommand, rendererSettings, withCliFlag } from './render-command.ts';

export interface SequenceSummary {
  kind: 'sequence';
  /** The output pattern. */
  out: string;
  width: number;
  height: number;
  /** Frames in the sequence (all variants). */
  frames: number;
  /** Frames rendered and written by this run. */
  written: number;
  /** Frames whose file existed (skipped; --overwrite renders them). */
  skipped: number;
  /** Seconds spent accumulating samples, over the written frames. */
  renderSeconds: number;
  totalSeconds: number;
  /** Path tracers created: 1 when every frame updated the first in place. */
  renderers: number;
  invalidSamples: number;
  adapter: string;
  /** What lit the frames, as a sentence (scene-lighting.ts). */
  lighting: string;
  /** Written files, in sequence order. */
  files: string[];
}

/** The sequence plan of a command over a loaded asset, with each frame's output path. */
export function planCommandSequence(gltf: GltfScene, command: RenderCommand): { items: GltfSequenceItem[]; paths: string[] } {
  try {
    const items = planGltfSequence(gltf, {
      ...(command.frames !== undefined ? { frames: command.frames, fps: command.fps ?? 24 } : {}),
      ...(command.at !== undefined ? { time: command.at } : {}),
      ...(command.turntable !== undefined ? { turntable: command.turntable } : {}),
      ...(command.variants !== undefined ? { variants: command.variants } : {}),
      ...(command.cameras !== undefined ? { cameras: command.cameras } : {}),
      aspect: command.width / command.height,
    });
    return { items, paths: outputPaths(command.out, sequencePatternValues(items), '--out') };
  } catch (error) {
    throw withCliFlag(error);
  }
}

/** Runs a sequence command; `io.device` renders on that device (default: one acquired for the run). */
export async function runSequenceCommand(command: RenderCommand, io: { stderr: ProgressStream; device?: GPUDevice } = { stderr: process.stderr }): Promise<SequenceSummary> {
  const t0 = performance.now();
  const resourcePolicy = commandResourcePolicy(command);
  const gltf = await loadGltfForCommand(command.scenePath as string, { camera: command.camera, variant: command.variant, animation: command.animation, at: command.at, aspectRatio: command.width / command.height, stderr: io.stderr, resourcePolicy });
  const { items, paths } = planCommandSequence(gltf, command);
  const todo: number[] = [];
  for (let i = 0; i < items.length; i++) if (command.overwrite || !(await frameFileExists(paths[i]!))) todo.push(i);
  let skipped = items.length - todo.length;
  if (skipped > 0) io.stderr.write(`sequence: ${skipped} of ${items.length} frames already on disk, skipped (--overwrite renders them again)\n`);
  // The asset's lights and materials are the same in every pose, so one choice holds for every frame.
  const { scene: lit, lighting } = await applyCliLighting({ ...gltf }, command, (text) => io.stderr.write(`note: ${text}\n`), resourcePolicy);
  const environment = lit.environmentMap !== undefined ? { environmentMap: lit.environmentMap } : {};
  // --orbit / --camera-position: one camera for every frame, placed around the loaded pose's bounds.
  const placed = command.orbit !== undefined || command.cameraPosition !== undefined ? applyCameraFlags({ ...gltf }, command).camera : undefined;
  const sequence = createSequenceRenderer({ ...rendererSettings(command), ...environment, ...(io.device ? { device: io.device } : {}) });
  const progress = createProgressBar(io.stderr, 'sequence');
  const files: string[] = [];
  let renderMs = 0;
  let invalidSamples = 0;
  let adapter = '';
  try {
    for (let k = 0; k < todo.length; k++) {
      const item = items[todo[k]!]!;
      const path = paths[todo[k]!]!;
      const frame = await poseGltfSequenceItem(gltf, item);
      const renderer = await sequence.show(placed !== undefined ? { ...frame.options, camera: placed } : applyCameraFlags(frame.options, { ...command, orbit: undefined, cameraPosition: undefined }));
      adapter ||= renderer.getSnapshot().adapter;
      const started = performance.now();
      const label = `frame ${[item.frame, item.variant, item.cameraName].filter((v) => v !== undefined).join(' ')} (${k + 1}/${todo.length})`;
      const stats = await accumulateImage(renderer, command, (done, total, estimate) => {
        // Frames still to come take the mean time of the frames so far (this one's estimate for the first).
        const frameSeconds = (performance.now() - started) / 1000;
        const perFrame = k > 0 ? renderMs / 1000 / k : frameSeconds + estimate.remainingSeconds;
        const remaining = estimate.remainingSeconds + (todo.length - k - 1) * perFrame;
        const fraction = (k + (estimate.fraction ?? done / total)) / todo.length;
        progress.update(done, total, { fraction, remainingSeconds: remaining, note: `${label}, this frame ~${formatDuration(estimate.remainingSeconds)} left, ~${formatDuration(perFrame)}/frame` });
      });
      renderMs += stats.renderMs;
      invalidSamples += stats.invalidSamples;
      // Without --overwrite a frame another process finished meanwhile is kept, not written twice.
      if (await writeFrameFile(path, await encodeOutput(renderer, command), command.overwrite ? 'replace' : 'create')) files.push(path);
      else skipped += 1;
    }
  } finally {
    progress.finish();
    sequence.destroy();
  }
  return {
    kind: 'sequence',
    out: command.out,
    width: command.width,
    height: command.height,
    frames: items.length,
    written: files.length,
    skipped,
    renderSeconds: renderMs / 1000,
    totalSeconds: (performance.now() - t0) / 1000,
    renderers: sequence.created,
    invalidSamples,
    adapter,
    lighting,
    files,
  };
}

export function formatSequenceSummary(s: SequenceSummary): string {
  const perFrame = s.written > 0 ? `, ${formatDuration(s.renderSeconds / s.written)}/frame rendering` : '';
  return [
    `wrote ${s.written} of ${s.frames} frames to ${s.out} (${s.width}x${s.height})${s.skipped > 0 ? `; ${s.skipped} already on disk, skipped (--overwrite renders them again)` : ''}`,
    `  ${formatDuration(s.renderSeconds)} rendering${perFrame}, ${formatDuration(s.totalSeconds)} total; ${s.renderers === 1 ? 'one path tracer updated in place' : `${s.renderers} path tracers`}`,
    `  ${s.lighting}`,
    `  adapter: ${s.adapter || 'none used'}${s.invalidSamples > 0 ? `; ${s.invalidSamples} invalid samples dropped` : ''}`,
  ].join('\n');
}
