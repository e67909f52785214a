/**
 * createAnimatedSceneRenderer: the animation adventure scene (the 0.2 API's "Animated Scene
 * Renderer", kept for its hosts) drawn with the raster PBR renderer. The renderer-independent animation core
 * (src/animation: clips, beats, route, movement, camera rigs) evaluates each frame; this module
 * uploads its joint matrices and morph weights (GPU skinning), places rigid parts, props and the
 * terrain, follows the camera rig, and completes the snapshot with what is really drawn.
 */
import type { Document } from '@gltf-transform/core';
import { readGltfDocument } from '../../io/gltf/document-reader.ts';
import { defaultResourcePolicy } from '../../io/resource-policy.ts';
import { mat4d } from 'wgpu-matrix';
import { createAnimatedSceneCore, type AnimatedSceneCore, type AnimatedSceneFrame } from '../../animation/animated-scene-core.ts';
import type { CameraRigOutput } from '../../animation/camera/camera-types.ts';
import { GpuRendererError } from '../../errors/gpu-renderer-error.ts';
import { describe, fail, requireInteger } from '../../errors/validate.ts';
import { loadGltfScene, type GltfScene } from '../../io/gltf/load-gltf-scene.ts';
import { resolveAnimationFrame } from '../../runtime/animation-frame.ts';
import { meshBounds } from '../gpu/geometry.ts';
import { createRasterRenderer } from '../renderer.ts';
import type { RasterRenderer } from '../types.ts';
import type { AnimatedPosedScene, AnimatedSceneRenderer, AnimatedSceneRendererOptions, AnimatedSceneSnapshot } from './animated-types.ts';
import { groundMesh } from './ground-mesh.ts';
import { appendGltfScene, appendMaterials, emptySceneParts, type SceneParts } from './merge-scene.ts';
import { modelRasterParts, type ModelDrawPart } from './model-meshes.ts';
import { primitivePropMesh } from './prop-meshes.ts';
import { createCharacterBounds } from './character-bounds.ts';

const knownKeys = new Set([
  'modelAsset', 'clipAssets', 'beats', 'route', 'props', 'camera', 'terrain', 'tolerances', 'canvas', 'width', 'height', 'propAssets', 'ground',
  'environment', 'environmentMap', 'environmentLighting', 'lights', 'toneMapping', 'exposure', 'msaa', 'shadow', 'format', 'device', 'powerPreference',
  'requestAnimationFrame', 'cancelAnimationFrame', 'onFrame', 'onError', 'renderMode',
]);

const DEFAULT_SKY: readonly number[] = [0.35, 0.4, 0.5];
const DEFAULT_KEY_LIGHT = { type: 'directional' as const, direction: [-0.4, -1, -0.3], intensity: 3, name: 'key' };

async function toDocument(asset: unknown): Promise<Document> {
  if (typeof asset === 'object' && asset !== null && typeof (asset as Document).getRoot === 'function') return asset as Document;
  if (asset instanceof ArrayBuffer || asset instanceof Uint8Array) {
    const bytes = asset instanceof Uint8Array ? asset : new Uint8Array(asset);
    // The glTF loader's reader: the validated container and JSON, the default resource policy
    // (bytes reference no external files) and its decoded-bytes budget.
    try {
      return (await readGltfDocument(bytes, [], { policy: defaultResourcePolicy })).document;
    } catch (cause) {
      throw new GpuRendererError('INVALID_OPTION', `modelAsset is not a readable GLB: ${(cause as Error).message}`, { field: 'modelAsset', cause });
    }
  }
  fail('INVALID_OPTION', 'modelAsset', `expected a glTF Document (@gltf-transform/core) or GLB bytes, got ${describe(asset)}`);
}

/** Nodes whose animation moves drawn geometry: skin joints and drawable nodes, with their ancestors. */
function animatedNodes(core: AnimatedSceneCore): Set<number> {
  const model = core.model;
  const out = new Set<number>();
  const add = (n: number): void => {
    for (let k = n; k >= 0 && !out.has(k); k = model.nodes[k]!.parent) out.add(k);
  };
  for (const d of model.drawables) {
    add(d.node);
    if (d.skin >= 0) for (const j of model.skins[d.skin]!.joints) add(j);
  }
  return out;
}

/**
 * What moves the character in the active beat: 'authored-travel' (a travel or jump beat whose
 * clip's authored root motion sets the distance, applied along the route), 'route-driven' (a travel
 * beat whose in-place clip slides along the route), 'authored' (a stationary beat keeping the
 * clip's root translation, as its profile allows), 'in-place' (a stationary beat holding its anchor).
 */
function rootMotionPolicy(kind: string, authoredClip: boolean, movement: 'authored' | 'in-place'): AnimatedSceneSnapshot['rootMotionPolicy'] {
  if (kind === 'travel' || kind === 'jump') return authoredClip ? 'authored-travel' : 'route-driven';
  return authoredClip && movement === 'authored' ? 'authored' : 'in-place';
}

export interface AnimatedRendererInternals {
  professional: boolean;
}

export async function createAnimatedRenderer(options: AnimatedSceneRendererOptions, internals: AnimatedRendererInternals): Promise<AnimatedSceneRenderer> {
  if (typeof options !== 'object' || options === null) fail('INVALID_OPTION', 'options', 'expected an options object');
  for (const key of Object.keys(options)) if (!knownKeys.has(key)) fail('INVALID_OPTION', key, 'unknown option');
  const renderMode = (options as { renderMode?: unknown }).renderMode;
  if (renderMode !== undefined && renderMode !== 'webgpu-pbr') {
    fail('INVALID_OPTION', 'renderMode', `only 'webgpu-pbr' is drawn: there is no 2D proxy path (got ${describe(renderMode)})`);
  }
  const document = await toDocument(options.modelAsset);
  const core = createAnimatedSceneCore({
    modelAsset: document,
    beats: options.beats,
    route: options.route,
    ...(options.clipAssets !== undefined ? { clipAssets: options.clipAssets } : {}),
    ...(options.props !== undefined ? { props: options.props } : {}),
    ...(options.camera !== undefined ? { camera: options.camera } : {}),
    ...(options.terrain !== undefined ? { terrain: options.terrain } : {}),
    ...(options.tolerances !== undefined ? { tolerances: options.tolerances } : {}),
    professional: internals.professional,
  });
  const model = core.model;
  const gltf: GltfScene = await loadGltfScene(document);

  // Scene parts: character materials first (glTF order, then a default), ground, props, rigid parts.
  const parts: SceneParts = emptySceneParts();
  appendMaterials(parts, gltf);
  const defaultMaterial = parts.materials.length;
  parts.materials.push({});
  const characterMaterials = parts.materials.length;
  const materialOf = (i: number): number => (i >= 0 && i < gltf.materials.length ? i : defaultMaterial);
  const characterTextures = new Set<number>();
  for (const m of gltf.materials) for (const [k, v] of Object.entries(m)) if (k.endsWith('Texture') && typeof v === 'object' && v !== null) characterTextures.add((v as { index: number }).index);

  const route = core.timeline.route.points;
  if (options.ground !== false) {
    const xs = route.map((p) => p.position[0]).concat(core.timeline.propGroundAnchors.map((a) => a.position[0]));
    const zs = route.map((p) => p.position[2]).concat(core.timeline.propGroundAnchors.map((a) => a.position[2]));
    const margin = 4;
    const min: [number, number] = [Math.min(...xs) - margin, Math.min(...zs) - margin];
    const max: [number, number] = [Math.max(...xs) + margin, Math.max(...zs) + margin];
    parts.meshes.push(groundMesh(core.timeline.terrain, min, max, 32));
    parts.instances.push({ mesh: parts.meshes.length - 1 });
  }
  const propAssets = options.propAssets ?? {};
  if (typeof propAssets !== 'object' || propAssets === null) fail('INVALID_OPTION', 'propAssets', 'expected { kind: glTF Document }');
  const propScenes = new Map<string, GltfScene>();
  for (const [kind, doc] of Object.entries(propAssets)) propScenes.set(kind, await loadGltfScene(doc));
  for (const anchor of core.timeline.propGroundAnchors) {
    const place = mat4d.translation(anchor.position);
    const scene = propScenes.get(anchor.kind);
    if (scene !== undefined) appendGltfScene(parts, scene, place);
    else {
      parts.meshes.push(primitivePropMesh(anchor.kind));
      parts.instances.push({ mesh: parts.meshes.length - 1, transform: Array.from(place) });
    }
  }
  const modelParts = modelRasterParts(model, materialOf, parts.meshes.length, 0);
  const staticInstanceOf = new Map<ModelDrawPart, number>();
  for (const part of modelParts.parts) {
    if (part.kind !== 'static') continue;
    staticInstanceOf.set(part, parts.instances.length);
    parts.instances.push({ mesh: part.index });
  }
  parts.meshes.push(...modelParts.meshes);

  const environmentGiven = options.environment !== undefined || options.environmentMap !== undefined || options.environmentLighting !== undefined;
  const lights = options.lights ?? (options.environmentLighting !== undefined ? [] : [DEFAULT_KEY_LIGHT]);
  const canvasElement = options.canvas as { width?: number; height?: number } | string | undefined;
  const canvasSize = typeof canvasElement === 'object' && canvasElement !== null ? { width: canvasElement.width, height: canvasElement.height } : {};
  const width = requireInteger(options.width ?? canvasSize.width ?? 640, 'width', { min: 1 });
  const height = requireInteger(options.height ?? canvasSize.height ?? 360, 'height', { min: 1 });
  const raster: RasterRenderer = await createRasterRenderer({
    width,
    height,
    ...parts,
    skinnedMeshes: modelParts.skinnedMeshes,
    skinnedInstances: modelParts.skinnedMeshes.map((_, i) => ({ mesh: i })),
    lights,
    ...(environmentGiven ? {} : { environment: { color: DEFAULT_SKY } }),
    ...(options.environment !== undefined ? { environment: options.environment } : {}),
    ...(options.environmentMap !== undefined ? { environmentMap: options.environmentMap } : {}),
    ...(options.environmentLighting !== undefined ? { environmentLighting: options.environmentLighting } : {}),
    ...(options.toneMapping !== undefined ? { toneMapping: options.toneMapping } : {}),
    ...(options.exposure !== undefined ? { exposure: options.exposure } : {}),
    ...(options.msaa !== undefined ? { msaa: options.msaa } : {}),
    ...(options.shadow !== undefined ? { shadow: options.shadow } : {}),
    ...(options.canvas !== undefined ? { canvas: options.canvas } : {}),
    ...(options.format !== undefined ? { format: options.format } : {}),
    ...(options.device !== undefined ? { device: options.device } : {}),
    ...(options.powerPreference !== undefined ? { powerPreference: options.powerPreference } : {}),
  });

  // What the snapshot reports about the drawn character.
  const relevant = animatedNodes(core);
  const bindPositions: number[] = [];
  for (const d of model.drawables) for (const p of model.meshes[d.mesh]!.primitives) bindPositions.push(...p.positions);
  const bindRadius = meshBounds(Float32Array.from(bindPositions)).radius;
  const characterBounds = createCharacterBounds(model);
  const skinnedParts = modelParts.parts.filter((p) => p.kind === 'skinned');
  const normalMapReady = skinnedParts.length > 0 && skinnedParts.every((p) => {
    const primitive = model.meshes[model.drawables[p.drawable]!.mesh]!.primitives[p.primitive]!;
    return primitive.material >= 0 && model.materials[primitive.material]!.hasNormalTexture && primitive.uvs !== null && primitive.normals !== null;
  });

  let snapshot: AnimatedSceneSnapshot | null = null;
  let lastFrame: { tMs: number; camera: CameraRigOutput } | null = null;
  let running = false;
  let handle: unknown;
  let clockStart: number | null = null;
  let clockMs = 0;
  let inFlight = false;
  let destroyed = false;
  let size = { width, height };
  const scheduler = resolveAnimationFrame(options);

  const screenBounds = (frame: AnimatedSceneFrame): { bounds: [number, number, number, number] | null; visible: boolean } => {
    const t = frame.camera.transform;
    const view = mat4d.lookAt(t.position, t.target, t.up);
    const proj = mat4d.perspective((t.fovYDegrees * Math.PI) / 180, size.width / size.height, 0.05, 1e4);
    const viewProj = mat4d.multiply(proj, view);
    const { min, max } = characterBounds.at(frame.sample.rootTransform, frame.worldMatrices, frame.jointMatrices, frame.morphWeights);
    const m = 0;
    let x0 = Infinity, y0 = Infinity, x1 = -Infinity, y1 = -Infinity;
    let inFront = 0;
    for (let c = 0; c < 8; c++) {
      const p = [c & 1 ? max[0]! + m : min[0]! - m, c & 2 ? max[1]! + m : min[1]! - m, c & 4 ? max[2]! + m : min[2]! - m];
      const clip = [0, 1, 2, 3].map((r) => viewProj[r]! * p[0]! + viewProj[4 + r]! * p[1]! + viewProj[8 + r]! * p[2]! + viewProj[12 + r]!);
      if (!(clip[3]! > 1e-6)) continue;
      inFront++;
      const sx = ((clip[0]! / clip[3]! + 1) / 2) * size.width;
      const sy = ((1 - clip[1]! / clip[3]!) / 2) * size.height;
      x0 = Math.min(x0, sx);
      y0 = Math.min(y0, sy);
      x1 = Math.max(x1, sx);
      y1 = Math.max(y1, sy);
    }
    if (inFront < 8) return { bounds: null, visible: inFront > 0 };
    const visible = x1 >= 0 && y1 >= 0 && x0 <= size.width && y0 <= size.height;
    return { bounds: [x0, y0, x1, y1], visible };
  };

  const renderAt = async (tMs: number): Promise<AnimatedSceneSnapshot> => {
    if (destroyed) throw new GpuRendererError('RENDERER_DESTROYED', 'the animated scene renderer was destroyed');
    const frame = core.frame(tMs);
    const root = frame.sample.rootTransform;
    for (const part of modelParts.parts) {
      const drawable = model.drawables[part.drawable]!;
      const nodeWorld = frame.worldMatrices.subarray(16 * drawable.node, 16 * drawable.node + 16);
      if (part.kind === 'skinned') {
        raster.setSkinPose(part.index, drawable.skin >= 0 ? frame.jointMatrices[drawable.skin]! : [], frame.morphWeights[part.drawable]);
        raster.setSkinnedInstanceTransform(part.index, drawable.skin >= 0 ? root : mat4d.multiply(root, nodeWorld));
      } else {
        raster.setInstanceTransform(staticInstanceOf.get(part)!, mat4d.multiply(root, nodeWorld));
      }
    }
    const t = frame.camera.transform;
    raster.setCamera({ position: t.position, target: t.target, up: t.up, fovYDegrees: t.fovYDegrees });
    const p = frame.snapshot.characterPosition;
    raster.setShadowFocus([p[0], p[1] + 1, p[2]], Math.max(4, 3 * bindRadius));
    const stats = await raster.render();
    lastFrame = { tMs, camera: frame.camera };
    const activeBeat = core.timeline.movement.beats.find((b) => b.beatId === frame.snapshot.activeBeatId);
    const activeClip = core.library.clips.get(frame.snapshot.activeClipId)!;
    const projected = screenBounds(frame);
    snapshot = Object.freeze({
      ...frame.snapshot,
      modelRenderable: modelParts.parts.length > 0,
      activeClipRenderable: modelParts.parts.length > 0 && activeClip.clip.channels.some((c) => relevant.has(c.node)),
      characterVisible: projected.visible,
      characterScreenBounds: projected.bounds,
      renderMode: 'webgpu-pbr' as const,
      textureCount: parts.textures.length,
      characterTextureCount: characterTextures.size,
      normalMapReady,
      rootMotionPolicy: rootMotionPolicy(activeBeat?.kind ?? 'stationary', activeClip.profile?.rootMotion === 'authored', activeBeat?.rootMotion ?? 'in-place'),
      drawCalls: stats.drawCalls,
      frameTimeMs: stats.frameTimeMs,
      running,
      size: { ...size },
    });
    return snapshot;
  };

  const stopLoop = (): void => {
    running = false;
    if (handle !== undefined) scheduler.cancel(handle);
    handle = undefined;
  };
  const tick = (timestamp: number): void => {
    handle = undefined;
    if (!running) return;
    clockStart ??= timestamp - clockMs;
    clockMs = timestamp - clockStart;
    if (!inFlight) {
      inFlight = true;
      // A tick that finds the previous frame still on the GPU skips drawing (frames never queue up).
      const fail = (error: unknown): void => {
        stopLoop();
        if (options.onError) options.onError(error);
        else console.error('[gpu-renderer] animated scene frame failed; the loop stopped', error);
      };
      renderAt(clockMs).then(
        (s) => {
          inFlight = false;
          try {
            options.onFrame?.(s);
          } catch (error) {
            fail(error);
          }
        },
        (error: unknown) => {
          inFlight = false;
          fail(error);
        },
      );
    }
    if (running) handle = scheduler.request(tick);
  };

  return {
    device: raster.device,
    start() {
      if (destroyed) throw new GpuRendererError('RENDERER_DESTROYED', 'the animated scene renderer was destroyed');
      if (running) return;
      running = true;
      clockStart = null;
      handle = scheduler.request(tick);
    },
    stop: stopLoop,
    resize(w, h) {
      raster.resize(w, h);
      size = { width: raster.width, height: raster.height };
    },
    renderOnce: (tMs) => renderAt(tMs ?? clockMs),
    getSnapshot: () => snapshot,
    setCamera: (camera) => core.setCamera(camera),
    setCameraViewMode: (mode) => core.setCameraViewMode(mode),
    applyCameraControl: (control) => core.applyCameraControl(control),
    readPixels: () => raster.readPixels(),
    posedScene(tMs) {
      const baked = core.bakePose(tMs, { material: (i) => materialOf(i) });
      const scene: AnimatedPosedScene = {
        lights,
        meshes: [...parts.meshes.slice(0, parts.meshes.length - modelParts.meshes.length), ...baked.meshes],
        instances: [],
        materials: parts.materials,
        textures: parts.textures,
        images: parts.images,
      };
      const staticInstances = parts.instances.filter((inst) => inst.mesh < scene.meshes!.length - baked.meshes.length);
      const offset = scene.meshes!.length - baked.meshes.length;
      scene.instances = [...staticInstances, ...baked.instances.map((inst) => ({ ...inst, mesh: inst.mesh + offset }))];
      const rig = lastFrame !== null && lastFrame.tMs === tMs ? lastFrame.camera : core.camera.evaluate(tMs, core.subject);
      scene.camera = { position: rig.transform.position, target: rig.transform.target, up: rig.transform.up, fovYDegrees: rig.transform.fovYDegrees };
      // The raster view's lighting; the path tracer takes one environment (a map, a sky or a colour).
      if (options.environmentMap !== undefined) scene.environmentMap = options.environmentMap;
      else if (options.environmentLighting !== undefined) scene.environmentLighting = options.environmentLighting;
      else scene.environment = { color: [...(options.environment?.color ?? DEFAULT_SKY)] };
      void characterMaterials;
      return scene;
    },
    destroy() {
      if (destroyed) return;
      destroyed = true;
      stopLoop();
      raster.destroy();
    },
  };
}

/**
 * Creates the animated scene renderer: a skinned glTF character playing `beats` along `route`
 * among `props`, followed by the camera rig, drawn with WebGPU PBR (GPU skinning, IBL, shadows).
 * Bad input is a typed error naming the field (model, clips, beats, route, camera).
 */
export function createAnimatedSceneRenderer(options: AnimatedSceneRendererOptions): Promise<AnimatedSceneRenderer> {
  return createAnimatedRenderer(options, { professional: false });
}
