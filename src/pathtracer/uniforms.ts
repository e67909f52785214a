import { CAMERA_ORTHOGRAPHIC, CAMERA_PERSPECTIVE, dynamicUniformStride, INDEX_NONE, PRESENTATION_LINEAR, PRESENTATION_TONEMAPPED, queueCounterSlots, TONE_MAPPING_ACES, TONE_MAPPING_AGX, TONE_MAPPING_LINEAR, TONE_MAPPING_NEUTRAL } from '../gpu-layout/constants.ts';
import { bounceUniformsLayout, frameUniformsLayout, resolveUniformsLayout, waveUniformsLayout } from '../gpu-layout/records.ts';
import { writeStruct } from '../gpu-layout/struct-layout.ts';
import type { WavefrontToneMapping } from '../scene/types.ts';
import type { WavefrontPathTracingComputeConfig } from './config.ts';
import type { Wave } from './tiling.ts';

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

/** One BounceUniforms record per depth, ping-ponging the two halves of the ray buffer. */
export function packBounceUniforms(maxDepth: number, capacity: number): ArrayBuffer {
  const data = new ArrayBuffer((maxDepth + 1) * dynamicUniformStride);
  for (let d = 0; d <= maxDepth; d++) {
    const even = d % 2 === 0;
    writeStruct(bounceUniformsLayout, new DataView(data, d * dynamicUniformStride, bounceUniformsLayout.size), 0, {
      depth: d,
      inCounter: even ? queueCounterSlots.rayCount0 : queueCounterSlots.rayCount1,
      outCounter: even ? queueCounterSlots.rayCount1 : queueCounterSlots.rayCount0,
      inBase: even ? 0 : capacity,
      outBase: even ? capacity : 0,
    });
  }
  return data;
}

/** WaveUniforms of a batch of waves, one per dynamic-offset slot. */
export function packWaveUniforms(waves: readonly Wave[]): ArrayBuffer {
  const data = new ArrayBuffer(Math.max(1, waves.length) * dynamicUniformStride);
  waves.forEach((w, i) => {
    writeStruct(waveUniformsLayout, new DataView(data, i * dynamicUniformStride, waveUniformsLayout.size), 0, {
      tileOrigin: w.tileOrigin,
      tileSize: w.tileSize,
      sampleIndex: w.sampleIndex,
      activeOffset: w.activeOffset ?? INDEX_NONE,
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
