import { CAMERA_ORTHOGRAPHIC, CAMERA_PERSPECTIVE, dynamicUniformStride, PRESENTATION_LINEAR, PRESENTATION_TONEMAPPED, queueLayoutWords, queueLengthWord, TONE_MAPPING_ACES, TONE_MAPPING_AGX, TONE_MAPPING_LINEAR, TONE_MAPPING_NEUTRAL } from '../gpu-layout/constants.ts';
import { bounceUniformsLayout, frameUniformsLayout, resolveUniformsLayout, waveUniformsLayout } from '../gpu-layout/records.ts';
import { writeStruct } from '../gpu-layout/struct-layout.ts';
import type { WavefrontToneMapping } from '../scene/types.ts';
import type { WavefrontPathTracingComputeConfig } from './config.ts';
import type { Wave } from './waves.ts';

export const toneMappingIds: Record<WavefrontToneMapping, number> = { neutral: TONE_MAPPING_NEUTRAL, aces: TONE_MAPPING_ACES, linear: TONE_MAPPING_LINEAR, agx: TONE_MAPPING_AGX };

export interface FrameSceneConstants {
  lightCount: number;
  environmentSelectProbability: number;
  /** Uniform environment radiance (src/lighting/gpu-lighting.ts); the config's colour when omitted. */
  environmentRadiance?: readonly number[];
  sceneCenter: readonly number[];
  sceneRadius: number;
  queueCapacity: number;
}

/** FrameUniforms: camera, environment, lights, scene extents. */
export function packFrameUniforms(c: WavefrontPathTracingComputeConfig, s: FrameSceneConstants): ArrayBuffer {
  const data = new ArrayBuffer(frameUniformsLayout.size);
  const camera = c.camera;
  writeStruct(frameUniformsLayout, new DataView(data), 0, {
    cameraPosition: camera.position,
    tanHalfFovY: camera.tanHalfFovY,
    cameraRight: camera.right,
    aspect: c.width / c.height,
    cameraUp: camera.trueUp,
    cameraKind: camera.kind === 'orthographic' ? CAMERA_ORTHOGRAPHIC : CAMERA_PERSPECTIVE,
    cameraForward: camera.forward,
    orthographicHalfHeight: camera.orthographicHalfHeight,
    environmentRadiance: s.environmentRadiance ?? c.environment,
    environmentSelectProbability: s.environmentSelectProbability,
    sceneCenter: s.sceneCenter,
    sceneRadius: s.sceneRadius,
    imageSize: [c.width, c.height],
    maxDepth: c.maxDepth,
    seed: c.seed,
    lightCount: s.lightCount,
    queueCapacity: s.queueCapacity,
    // Ray cones (Akenine-Moller et al. 2021, eq. 30): the spread angle of one pixel.
    pixelSpreadAngle: Math.atan((2 * camera.tanHalfFovY) / c.height),
  });
  return data;
}

/**
 * One BounceUniforms record per depth: bounce d traces ray queue d % 2 (whose length word is d's),
 * sorting its rays into the shading queue (hits, escaped rays), shades that and fills ray queue
 * (d + 1) % 2; it traces the shadow rays bounce d - 1 queued and queues its own into the shadow
 * queue (traced by bounce d + 1, so one shadow queue serves every bounce).
 */
export function packBounceUniforms(maxDepth: number, capacity: number): ArrayBuffer {
  const data = new ArrayBuffer((maxDepth + 1) * dynamicUniformStride);
  const rayQueue = (d: number): number => queueLayoutWords.entriesBase + (d % 2) * capacity;
  for (let d = 0; d <= maxDepth; d++) {
    writeStruct(bounceUniformsLayout, new DataView(data, d * dynamicUniformStride, bounceUniformsLayout.size), 0, {
      depth: d,
      rayCount: queueLengthWord(d, 'rays'),
      rayQueue: rayQueue(d),
      shadowCount: queueLengthWord(d - 1, 'shadows'),
      shadowQueue: queueLayoutWords.entriesBase + 2 * capacity,
      nextRayCount: queueLengthWord(d + 1, 'rays'),
      nextRayQueue: rayQueue(d + 1),
      nextShadowCount: queueLengthWord(d, 'shadows'),
      hitCount: queueLengthWord(d, 'hits'),
      missCount: queueLengthWord(d, 'misses'),
      shadingQueue: queueLayoutWords.entriesBase + 3 * capacity,
      shadingQueueLast: queueLayoutWords.entriesBase + 4 * capacity - 1,
    });
  }
  return data;
}

/** WaveUniforms of a batch of waves, one per dynamic-offset slot. */
export function packWaveUniforms(waves: readonly Wave[]): ArrayBuffer {
  const data = new ArrayBuffer(Math.max(1, waves.length) * dynamicUniformStride);
  waves.forEach((w, i) => {
    writeStruct(waveUniformsLayout, new DataView(data, i * dynamicUniformStride, waveUniformsLayout.size), 0, {
      firstPath: w.firstPath,
      firstSample: w.firstSample,
      pathCount: w.pathCount,
      passes: w.passes,
      list: w.list ? 1 : 0,
    });
  });
  return data;
}

/** ResolveUniforms: `exposure` is the linear multiplier (exposure * 2^exposureEv). */
export function packDisplayUniforms(width: number, height: number, toneMapping: WavefrontToneMapping, exposure: number, output: 'tonemapped' | 'linear' = 'tonemapped'): ArrayBuffer {
  const data = new ArrayBuffer(resolveUniformsLayout.size);
  writeStruct(resolveUniformsLayout, new DataView(data), 0, {
    imageSize: [width, height],
    toneMapping: toneMappingIds[toneMapping],
    exposure,
    output: output === 'linear' ? PRESENTATION_LINEAR : PRESENTATION_TONEMAPPED,
  });
  return data;
}
