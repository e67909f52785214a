/** The render command's closing summary (separate from the renderer so it is testable without a GPU). */
import type { WavefrontRendererSnapshot } from '../pathtracer/types.ts';
import { formatDuration } from './progress.ts';

export interface RenderSummary {
  width: number;
  height: number;
  /** Sample passes: the most samples any pixel took. */
  samplesPerPixel: number;
  /** Mean samples per pixel (fewer than samplesPerPixel with --noise). */
  meanSamplesPerPixel?: number;
  /** What ended the render: the spp ceiling, --time or --noise (every pixel converged). */
  stoppedBy?: 'spp' | 'time' | 'noise';
  /** The denoiser that ran ('oidn', 'atrous'), if any. */
  denoised?: string;
  /** AOV layers written into the .exr. */
  aovs?: readonly string[];
  /**
   * Seconds of the first frame, rendered before the clock starts: drivers that compile pipelines
   * on their first dispatch compile here. Undefined: not measured apart.
   */
  firstFrameSeconds?: number;
  /** Samples per pixel of the first frame. */
  firstFrameSamplesPerPixel?: number;
  /** Seconds spent in the renderFrame calls after the first frame (what --time limits). */
  renderSeconds: number;
  /** Seconds from start to the written PNG. */
  totalSeconds: number;
  /** Pixel samples taken after the first frame / renderSeconds (the first frame's, for a one-frame render). */
  samplesPerSecond: number;
  rays: number;
  raysPerSecond: number;
  invalidSamples: number;
  adapter: string;
  /** What lit the scene, as a sentence ("lit by the scene's 2 punctual lights"); see scene-lighting.ts. */
  lighting?: string;
  /** How the geometry is stored and traced (describeGeometry). */
  geometry?: string;
  out: string;
}

/** The geometry line: placements of shared meshes, flattened triangles and the scene's GPU memory. */
export function describeGeometry(s: Pick<WavefrontRendererSnapshot, 'instancing' | 'memory'>): string {
  const i = s.instancing;
  const mb = (bytes: number): string => `${(bytes / 2 ** 20).toFixed(1)} MiB`;
  const count = (n: number): string => (n < 1000 ? String(n) : formatRate(n));
  const shared = i.placements > 0
    ? `${count(i.placements)} placements of ${i.sharedMeshes} shared mesh${i.sharedMeshes === 1 ? '' : 'es'} (${count(i.bottomLevelTriangles)} triangles stored once for ${count(i.placedTriangles)} placed, ${i.bytesPerPlacement} bytes per placement), `
    : '';
  return `geometry: ${shared}${count(i.flattenedTriangles)} triangles flattened (--instancing ${i.mode}); scene buffers ${mb(s.memory.sceneBytes)}`;
}

/** Engineering notation: 1234567 -> "1.23 M". */
export function formatRate(value: number): string {
  if (!Number.isFinite(value)) return '?';
  const units = ['', ' k', ' M', ' G', ' T'];
  let v = value;
  let u = 0;
  while (Math.abs(v) >= 1000 && u < units.length - 1) {
    v /= 1000;
    u++;
  }
  return `${v.toPrecision(3)}${units[u]}`;
}

export function formatSummary(s: RenderSummary): string {
  const adaptive = s.meanSamplesPerPixel !== undefined && s.meanSamplesPerPixel < s.samplesPerPixel - 1e-9 ? `, mean ${s.meanSamplesPerPixel.toFixed(1)}` : '';
  const extras = [
    s.stoppedBy && s.stoppedBy !== 'spp' ? `stopped by ${s.stoppedBy === 'time' ? 'the time limit' : 'the noise target'}` : '',
    s.denoised ? `denoised (${s.denoised === 'oidn' ? 'OIDN' : s.denoised === 'atrous' ? 'a-trous' : s.denoised})` : '',
    s.aovs && s.aovs.length > 0 ? `AOVs ${s.aovs.join(', ')}` : '',
  ].filter((e) => e !== '');
  return [
    `wrote ${s.out} (${s.width}x${s.height}, ${s.samplesPerPixel} spp${adaptive})${extras.length > 0 ? `; ${extras.join('; ')}` : ''}`,
    `  ${formatRate(s.samplesPerSecond)}samples/s, ${formatRate(s.raysPerSecond)}rays/s (${formatRate(s.rays)}rays), ` +
      `${formatDuration(s.renderSeconds)} rendering, ${formatDuration(s.totalSeconds)} total`,
    ...(s.firstFrameSeconds !== undefined
      ? [`  first frame (${s.firstFrameSamplesPerPixel ?? '?'} spp, with shader compilation) ${formatDuration(s.firstFrameSeconds)}, before the clock: not in the rendering time, rates or --time`]
      : []),
    ...(s.lighting !== undefined ? [`  ${s.lighting}`] : []),
    ...(s.geometry !== undefined ? [`  ${s.geometry}`] : []),
    `  adapter: ${s.adapter}${s.invalidSamples > 0 ? `; ${s.invalidSamples} invalid samples dropped` : ''}`,
  ].join('\n');
}
