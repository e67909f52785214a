/** The `render` command: load a scene, path trace it in small increments with progress, write a PNG. */
import { createWavefrontPathTracingComputeRenderer } from '../pathtracer/index.ts';
import type { WavefrontPathTracingRenderer } from '../pathtracer/types.ts';
import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import { createCornellBoxScene } from '../scene/cornell-box.ts';
import type { WavefrontSceneDescription } from '../scene/types.ts';
import type { EnvironmentMapInput } from '../lighting/environment-map.ts';
import { applyEnvironmentFlags } from './environment-flags.ts';
import { writePng } from '../post/png-node.ts';
import { createProgressBar, type ProgressStream } from './progress.ts';
import type { RenderSummary } from './render-format.ts';
import { isGltfPath, type RenderCommand } from './args.ts';

export type { RenderSummary } from './render-format.ts';

/**
 * The scene to render: the Cornell box, a glTF 2.0 asset (.glb / .gltf, by extension; its loader
 * warnings go to `stderr`) or a scene JSON file.
 */
export async function loadScene(
  scenePath: string | undefined,
  options: { camera?: string; variant?: string; stderr?: ProgressStream } = {},
): Promise<WavefrontSceneDescription & { environmentMap?: EnvironmentMapInput }> {
  if (scenePath === undefined) return createCornellBoxScene();
  if (isGltfPath(scenePath)) {
    // Loaded on demand so JSON scenes never pull in the glTF reader and its decoders.
    const { loadGltfScene } = await import('../io/gltf/load-gltf-scene.ts');
    const gltf = await loadGltfScene(scenePath, { camera: options.camera, variant: options.variant });
    for (const warning of gltf.warnings) options.stderr?.write(`warning: ${warning}\n`);
    // Spreading keeps the renderer's scene keys only; the loader's metadata is non-enumerable.
    return { ...gltf };
  }
  // Scene JSON: its `uri` images are decoded and its `gltf` references loaded and merged.
  const { loadSceneFile } = await import('../io/scene-file-loader.ts');
  const file = await loadSceneFile(scenePath);
  for (const warning of file.warnings) options.stderr?.write(`warning: ${warning}\n`);
  return file.scene;
}

export async function runRenderCommand(command: RenderCommand, io: { stderr: ProgressStream } = { stderr: process.stderr }): Promise<RenderSummary> {
  const t0 = performance.now();
  const scene = await applyEnvironmentFlags(await loadScene(command.scenePath, { camera: command.camera, variant: command.variant, stderr: io.stderr }), command);
  const renderer: WavefrontPathTracingRenderer = await createWavefrontPathTracingComputeRenderer({
    width: command.width,
    height: command.height,
    maxDepth: command.maxDepth,
    samplesPerPixel: command.sppPerFrame,
    seed: command.seed,
    toneMapping: command.toneMapping,
    exposure: command.exposure,
    ...scene,
  });
  try {
    const progress = createProgressBar(io.stderr);
    let accumulated = 0;
    let rays = 0;
    let invalidSamples = 0;
    let renderMs = 0;
    progress.update(0, command.spp);
    while (accumulated < command.spp) {
      const spp = Math.min(command.sppPerFrame, command.spp - accumulated);
      const start = performance.now();
      const stats = await renderer.renderFrame({ samplesPerPixel: spp });
      renderMs += performance.now() - start;
      accumulated = stats.samplesAccumulated;
      rays += stats.rays.total;
      invalidSamples += stats.invalidSamples;
      progress.update(accumulated, command.spp);
      if (stats.samplesAdded <= 0) throw new GpuRendererError('INVALID_STATE', 'renderFrame added no samples');
    }
    progress.finish();
    const pixels = await renderer.readPixels();
    await writePng(command.out, pixels);
    const renderSeconds = renderMs / 1000;
    return {
      width: command.width,
      height: command.height,
      samplesPerPixel: accumulated,
      renderSeconds,
      totalSeconds: (performance.now() - t0) / 1000,
      samplesPerSecond: (command.width * command.height * accumulated) / renderSeconds,
      rays,
      raysPerSecond: rays / renderSeconds,
      invalidSamples,
      adapter: renderer.getSnapshot().adapter,
      out: command.out,
    };
  } finally {
    renderer.destroy();
  }
}
