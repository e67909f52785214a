/** `gpu-renderer render` arguments (no I/O): the option table's values, then the rules between options. */
import { imageFileFormatFromPath } from '../io/images/image-file.ts';
import { hasCameraPlaceholder, hasFramePlaceholder, hasVariantPlaceholder } from '../sequence/output-pattern.ts';
import type { HelpCommand, RenderCommand } from './commands.ts';
import { formatOptions, parseOptions } from './option-table.ts';
import { invalidOption } from './option-values.ts';
import { renderDefaults, renderOptionSections, renderOptions } from './render-options.ts';

export const usage = `Usage: gpu-renderer render [scene.json | model.glb | model.gltf] [options]
       gpu-renderer farm <submit | worker | status> [options]   (see gpu-renderer farm --help)

Renders a scene with the WebGPU wavefront path tracer and writes a PNG, OpenEXR or Radiance HDR
image (by the extension of --out). The scene is a scene JSON file or a glTF 2.0 asset (.glb or
.gltf, chosen by extension). Without a scene file it renders the built-in Cornell box.
${renderOptionSections.map((section) => `\n${section.title}\n${formatOptions(section.options)}`).join('')}`;

/** A command that renders a sequence of images (frames, a turntable or variants) rather than one still. */
export function isSequence(command: Pick<RenderCommand, 'frames' | 'turntable' | 'variants' | 'cameras'>): boolean {
  return command.frames !== undefined || command.turntable !== undefined || command.variants !== undefined || command.cameras !== undefined;
}

/** True for paths the CLI loads as glTF 2.0 (.glb, .gltf; case-insensitive). */
export function isGltfPath(path: string): boolean {
  return /\.(glb|gltf)$/i.test(path);
}

/** Parses the arguments after `render` (e.g. `['scene.json', '--spp', '16']`). */
export function parseRenderArgs(argv: readonly string[]): RenderCommand | HelpCommand {
  const command: RenderCommand = { kind: 'render', scenePath: undefined, ...renderDefaults, aovs: [] };
  const parsed = parseOptions(argv, renderOptions, command);
  if (parsed.kind === 'help') return { kind: 'help', text: usage };
  const [scenePath, second] = parsed.rest;
  if (second !== undefined) invalidOption('scene', `only one scene file may be given (got ${JSON.stringify(scenePath)} and ${JSON.stringify(second)})`);
  command.scenePath = scenePath;
  checkCombinations(command, parsed.given);
  return command;
}

/** The rules between options (and the output format from --out's extension). */
function checkCombinations(command: RenderCommand, given: ReadonlySet<string>): void {
  if (!given.has('--spp-per-frame')) command.sppPerFrame = Math.min(command.sppPerFrame, command.spp);
  try {
    command.format = imageFileFormatFromPath(command.out);
  } catch {
    invalidOption('--out', `cannot tell the image format from ${JSON.stringify(command.out)} (expected .png, .exr or .hdr)`);
  }
  if (command.aovs.length > 0 && command.format !== 'exr') invalidOption('--aov', 'AOV layers need an .exr output');
  if (command.half && command.format !== 'exr') invalidOption('--half', 'applies to .exr output only');
  if (command.minSpp !== undefined && command.noiseThreshold === undefined) invalidOption('--min-spp', 'applies with --noise');
  if (command.minSpp !== undefined && command.minSpp > command.spp) invalidOption('--min-spp', `must be <= --spp (${command.spp})`);
  if (command.cameraTarget !== undefined && command.cameraPosition === undefined) invalidOption('--camera-target', 'needs --camera-position (or use --orbit)');
  if (command.orbit !== undefined && command.cameraPosition !== undefined) invalidOption('--orbit', 'cannot be combined with --camera-position');
  if (command.camera !== undefined && (command.orbit !== undefined || command.cameraPosition !== undefined)) {
    invalidOption('--camera', `names a camera of the asset; ${command.orbit !== undefined ? '--orbit' : '--camera-position'} places one instead`);
  }
  const gltfOnly = [['--camera', command.camera], ['--variant', command.variant], ['--animation', command.animation], ['--at', command.at], ['--frames', command.frames], ['--turntable', command.turntable], ['--variants', command.variants], ['--cameras', command.cameras]] as const;
  for (const [flag, value] of gltfOnly) {
    if (value !== undefined && (command.scenePath === undefined || !isGltfPath(command.scenePath))) invalidOption(flag, 'applies to glTF scenes (.glb or .gltf) only');
  }
  if (command.at !== undefined && command.frames !== undefined) invalidOption('--at', '--frames pose frame f at f / fps; give one of --at and --frames');
  if (command.fps !== undefined && command.frames === undefined) invalidOption('--fps', 'applies with --frames');
  if (command.variant !== undefined && command.variants !== undefined) invalidOption('--variants', 'give one of --variant and --variants');
  if (command.camera !== undefined && command.cameras !== undefined) invalidOption('--cameras', 'give one of --camera and --cameras');
  if (command.turntable !== undefined && command.cameras !== undefined) invalidOption('--cameras', 'a turntable brings its own camera; give one of --turntable and --cameras');
  const placed = command.orbit !== undefined ? '--orbit' : command.cameraPosition !== undefined ? '--camera-position' : undefined;
  if (placed !== undefined && command.turntable !== undefined) invalidOption('--turntable', `a turntable brings its own camera; give one of --turntable and ${placed}`);
  if (placed !== undefined && command.cameras !== undefined) invalidOption('--cameras', `give one of --cameras and ${placed}`);
  if (command.overwrite === true && !isSequence(command)) invalidOption('--overwrite', 'applies to sequences (--frames, --turntable, --variants, --cameras)');
  if (isSequence(command)) {
    const frameCount = command.frames?.length ?? command.turntable ?? 1;
    if (frameCount > 1 && !hasFramePlaceholder(command.out)) invalidOption('--out', `${frameCount} frames need a frame number in the file name: put #### where it goes (e.g. shot-####.png)`);
    const variantCount = command.variants === 'all' ? Infinity : (command.variants?.length ?? 1);
    if (variantCount > 1 && !hasVariantPlaceholder(command.out)) invalidOption('--out', 'several variants need {variant} in the file name (e.g. shoe-{variant}.png)');
    const cameraCount = command.cameras === 'all' ? Infinity : (command.cameras?.length ?? 1);
    if (cameraCount > 1 && !hasCameraPlaceholder(command.out)) invalidOption('--out', 'several cameras need {camera} in the file name (e.g. room-{camera}.png)');
  }
}
