import { loopClipTimeMs } from '../pose/evaluate-clip.ts';
import type { ClipLayer } from '../pose/evaluate-layers.ts';
import type { AnimationBeat } from './beats.ts';
import type { MovementPlan } from './movement.ts';

export interface BeatLayers {
  readonly layers: ClipLayer[];
  /** Index (in play order) of the beat whose window [startMs, endMs) holds the time; the last beat after the end. */
  readonly activeIndex: number;
  /** Progress of the cross-fade in progress (0..1), 1 when none. */
  readonly blendProgress: number;
  /** Clip time of the active beat's layer. */
  readonly activeClipTimeMs: number;
}

/**
 * Clip layers at scene time `tMs`. The boundary between beats A and B (B starting at T) cross-fades
 * linearly over [T - A.outMs, T + B.inMs]: A fades out over its last outMs, B fades in over its
 * first inMs, and B's clip starts playing when its fade begins. A beat's clip loops over its
 * window. The first beat's inMs and the last beat's outMs have nothing to blend with and are
 * ignored; after the last beat its clip keeps looping.
 */
export function beatLayersAt(beats: readonly AnimationBeat[], movement: MovementPlan, tMs: number): BeatLayers {
  const t = Math.max(0, tMs);
  let k = beats.length - 1;
  while (k > 0 && beats[k].startMs > t) k--;
  const layerStart = (j: number): number => (j === 0 ? 0 : beats[j].startMs - beats[j - 1].blendOutMs);
  const layer = (j: number, weight: number): ClipLayer => ({
    clip: beats[j].clip.clip,
    clipTimeMs: loopClipTimeMs(t - layerStart(j), beats[j].clip.clip.durationS),
    weight,
    rootMotion: movement.beats[j].rootMotion,
    root: beats[j].clip.root,
  });
  const beat = beats[k];
  if (k > 0) {
    const previous = beats[k - 1];
    const window = previous.blendOutMs + beat.blendInMs;
    if (window > 0 && t < beat.startMs + beat.blendInMs) {
      const p = (t - (beat.startMs - previous.blendOutMs)) / window;
      const active = layer(k, p);
      return { layers: [layer(k - 1, 1 - p), active], activeIndex: k, blendProgress: p, activeClipTimeMs: active.clipTimeMs };
    }
  }
  if (k < beats.length - 1) {
    const next = beats[k + 1];
    const window = beat.blendOutMs + next.blendInMs;
    const fadeStart = next.startMs - beat.blendOutMs;
    if (window > 0 && t >= fadeStart) {
      const p = (t - fadeStart) / window;
      const active = layer(k, 1 - p);
      return { layers: [active, layer(k + 1, p)], activeIndex: k, blendProgress: p, activeClipTimeMs: active.clipTimeMs };
    }
  }
  const only = layer(k, 1);
  return { layers: [only], activeIndex: k, blendProgress: 1, activeClipTimeMs: only.clipTimeMs };
}
