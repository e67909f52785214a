/**
 * `createRasterRenderer`: the forward WebGPU raster renderer of the shared scene representation.
 * Per frame: skinning compute pass -> shadow map pass -> multisampled forward pass (opaque, the
 * environment behind them, then blended surfaces back to front) resolved into linear radiance ->
 * display pass (exposure, the path tracer's tone mapping, sRGB) into the canvas or offscreen target.
 */
import { mat4 } from 'wgpu-matrix';
import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import { fail, requireInteger } from '../errors/validate.ts';
import { allocateStructArray, writeStruct } from '../gpu-layout/struct-layout.ts';
import { acquireGpuDevice, getGpu } from '../gpu/acquire-device.ts';
import { BufferUsage, MapMode, TextureUsage } from '../gpu/webgpu-constants.ts';
import { createEnvironmentLighting } from '../lighting/environment-lighting.ts';
import { validateEnvironmentMap, type EnvironmentMap } from '../lighting/environment-map.ts';
import { packPunctualLights, type PunctualLight } from '../lighting/punctual-lights.ts';
import { sunSolidAngle } from '../lighting/sun-light.ts';
import { readTexturePixels } from '../runtime/read-pixels.ts';
import { createCanvasTarget, createOffscreenTarget, resolveCanvas, type RenderTarget } from '../runtime/render-target.ts';
import type { GpuRendererFormat } from '../runtime/renderer-types.ts';
import { toneMappingModeIds } from '../film/tone-mapping.ts';
import { cameraViewProjection, lightViewProjection, towardsViewer, validateRasterCamera, type RasterCamera } from './camera-matrices.ts';
import { computeBrdfLut, createConstantEnvironment, createMapEnvironment, type RasterEnvironment } from './gpu/environment.ts';
import { uploadMeshStreams, type GpuMeshStreams } from './gpu/geometry.ts';
import { createGpuMaterial, type GpuRasterMaterial } from './gpu/materials.ts';
import { createRasterPipelines, DEPTH_FORMAT, HDR_FORMAT, SHADOW_FORMAT, type RasterPipelines } from './gpu/pipelines.ts';
import { rasterConstants, rasterDrawLayout, rasterFrameLayout } from './gpu/raster-layout.ts';
import { createRasterSkinning } from './gpu/skinning.ts';
import { createRasterTextures } from './gpu/textures.ts';
import { validateRasterOptions } from './options.ts';
import { normalizeRasterScene, validateTransform } from './scene/raster-scene.ts';
import type { RasterFrameStats, RasterRenderer, RasterRendererOptions } from './types.ts';

const DRAW_STRIDE = 256;

interface Draw {
  streams: GpuMeshStreams;
  vertexBuffers: { buffer: GPUBuffer; offset: number }[];
  material: GpuRasterMaterial;
  transform: Float64Array;
  visible: boolean;
  /** Index in `instances` or `skinnedInstances`. */
  kind: 'static' | 'skinned';
  index: number;
}

function transformPoint(m: ArrayLike<number>, p: readonly number[]): [number, number, number] {
  return [0, 1, 2].map((r) => m[r]! * p[0]! + m[4 + r]! * p[1]! + m[8 + r]! * p[2]! + m[12 + r]!) as [number, number, number];
}

function maxScale(m: ArrayLike<number>): number {
  return Math.max(Math.hypot(m[0]!, m[1]!, m[2]!), Math.hypot(m[4]!, m[5]!, m[6]!), Math.hypot(m[8]!, m[9]!, m[10]!));
}

/** Inverse transpose of the upper 3x3 as three column vectors, and the determinant's sign. */
function normalMatrix(m: ArrayLike<number>): { columns: number[][]; sign: number } {
  const a = (r: number, c: number): number => m[4 * c + r]!;
  const cof = [
    [a(1, 1) * a(2, 2) - a(1, 2) * a(2, 1), a(1, 2) * a(2, 0) - a(1, 0) * a(2, 2), a(1, 0) * a(2, 1) - a(1, 1) * a(2, 0)],
    [a(0, 2) * a(2, 1) - a(0, 1) * a(2, 2), a(0, 0) * a(2, 2) - a(0, 2) * a(2, 0), a(0, 1) * a(2, 0) - a(0, 0) * a(2, 1)],
    [a(0, 1) * a(1, 2) - a(0, 2) * a(1, 1), a(0, 2) * a(1, 0) - a(0, 0) * a(1, 2), a(0, 0) * a(1, 1) - a(0, 1) * a(1, 0)],
  ];
  const det = a(0, 0) * cof[0]![0]! + a(0, 1) * cof[0]![1]! + a(0, 2) * cof[0]![2]!;
  // Inverse transpose = cof / det; (row r, column c) = cof[r][c] / det. Column c = (cof[0][c], cof[1][c], cof[2][c]) / det.
  const columns = [0, 1, 2].map((c) => [cof[0]![c]! / det, cof[1]![c]! / det, cof[2]![c]! / det, 0]);
  return { columns, sign: det < 0 ? -1 : 1 };
}

/** Creates the raster renderer; validates the whole scene first (typed errors name the field). */
export async function createRasterRenderer(options: RasterRendererOptions): Promise<RasterRenderer> {
  const validated = validateRasterOptions(options, 16384);
  const scene = normalizeRasterScene(options);
  let environmentMap: EnvironmentMap | null = null;
  const lights: PunctualLight[] = [...scene.lights];
  let sunLight = -1;
  if (options.environmentMap !== undefined && options.environmentLighting !== undefined) fail('INVALID_OPTION', 'environmentLighting', 'give environmentMap or environmentLighting, not both');
  if (options.environmentMap !== undefined) environmentMap = validateEnvironmentMap(options.environmentMap);
  if (options.environmentLighting !== undefined) {
    const sky = createEnvironmentLighting(options.environmentLighting);
    environmentMap = sky.map;
    if (sky.sun !== null) {
      const omega = sunSolidAngle(sky.sun);
      sunLight = lights.length;
      lights.push({ type: 'directional', position: [0, 0, 0], direction: [-sky.sun.direction[0], -sky.sun.direction[1], -sky.sun.direction[2]], intensity: sky.sun.radiance.map((c) => c * omega) as [number, number, number], range: Infinity, innerConeAngle: 0, outerConeAngle: Math.PI / 4 });
    }
  }
  let uniformEnvironment: [number, number, number] | null = null;
  if (options.environment !== undefined) {
    if (environmentMap !== null) fail('INVALID_OPTION', 'environment', 'give one of environment, environmentMap and environmentLighting');
    const c = options.environment?.color;
    if (!Array.isArray(c) || c.length !== 3 || c.some((x) => typeof x !== 'number' || !Number.isFinite(x) || x < 0)) fail('INVALID_OPTION', 'environment.color', 'expected three finite radiances >= 0');
    uniformEnvironment = [c[0]!, c[1]!, c[2]!];
  }
  let camera: RasterCamera | null = options.camera === undefined ? null : validateRasterCamera(options.camera);
  let shadowLight = -1;
  if (validated.shadow !== null) {
    if (validated.shadow.light !== undefined) {
      shadowLight = validated.shadow.light;
      if (lights[shadowLight]!.type === 'point') fail('INVALID_OPTION', 'shadow.light', 'point lights cast no shadow map here; choose a directional or spot light');
    } else {
      shadowLight = sunLight >= 0 ? sunLight : lights.findIndex((l) => l.type === 'directional');
    }
  }

  const acquired = await acquireGpuDevice({ device: options.device, powerPreference: options.powerPreference });
  const { device, ownsDevice } = acquired;
  const canvas = options.canvas === undefined ? undefined : resolveCanvas(options.canvas);
  let format: GpuRendererFormat = options.format ?? 'rgba8unorm';
  if (canvas && options.format === undefined) format = ((await getGpu())?.getPreferredCanvasFormat() as GpuRendererFormat | undefined) ?? 'bgra8unorm';
  let target: RenderTarget;
  try {
    if (canvas) {
      canvas.width = validated.width;
      canvas.height = validated.height;
    }
    target = canvas ? createCanvasTarget(canvas, device, format, false) : createOffscreenTarget(device, format, validated.width, validated.height);
  } catch (error) {
    if (ownsDevice) device.destroy();
    throw error;
  }
  device.pushErrorScope('validation');
  let pipelines: RasterPipelines;
  try {
    pipelines = await createRasterPipelines(device, validated.msaa);
  } catch (error) {
    await device.popErrorScope();
    if (ownsDevice) device.destroy();
    throw error;
  }
  const textures = createRasterTextures(device, options, scene.materials);
  const materials = scene.materials.map((m) => createGpuMaterial(device, pipelines.drawLayouts[1]!, m, textures));
  const meshStreams = scene.base.meshes.map((m, i) => uploadMeshStreams(device, m, `mesh ${i}`));
  const skinnedStreams = scene.skinnedMeshes.map((m, i) => uploadMeshStreams(device, m.mesh, `skinned mesh ${i}`));
  const skinning = createRasterSkinning(device, pipelines, scene.skinnedMeshes, scene.skinnedInstances.map((s) => s.mesh));
  const shBlank = device.createBuffer({ size: 9 * 16, usage: BufferUsage.STORAGE });
  const brdfLut = computeBrdfLut(device, pipelines, shBlank);
  const environment: RasterEnvironment =
    environmentMap !== null
      ? createMapEnvironment(device, pipelines, environmentMap)
      : createConstantEnvironment(device, uniformEnvironment !== null ? rasterConstants.ENVIRONMENT_UNIFORM : rasterConstants.ENVIRONMENT_BLACK);

  const draws: Draw[] = [];
  scene.base.instances.forEach((inst, i) => {
    const streams = meshStreams[inst.mesh]!;
    const material = materials[inst.material ?? scene.base.meshMaterials[inst.mesh]!]!;
    draws.push({ streams, vertexBuffers: streams.buffers, material, transform: scene.instanceTransforms[i]!, visible: true, kind: 'static', index: i });
  });
  scene.skinnedInstances.forEach((inst, i) => {
    const streams = skinnedStreams[inst.mesh]!;
    const gpu = skinning.instances[i]!;
    const vertexBuffers = [...streams.buffers];
    vertexBuffers[0] = { buffer: skinning.output, offset: gpu.positions };
    if (gpu.normals !== null) vertexBuffers[1] = { buffer: skinning.output, offset: gpu.normals };
    if (gpu.tangents !== null) vertexBuffers[2] = { buffer: skinning.output, offset: gpu.tangents };
    draws.push({ streams, vertexBuffers, material: materials[scene.skinnedMeshes[inst.mesh]!.material]!, transform: inst.transform, visible: true, kind: 'skinned', index: i });
  });

  const frameBuffer = device.createBuffer({ label: 'raster frame', size: rasterFrameLayout.size, usage: BufferUsage.UNIFORM | BufferUsage.COPY_DST });
  const drawBuffer = device.createBuffer({ label: 'raster draws', size: Math.max(1, draws.length) * DRAW_STRIDE, usage: BufferUsage.UNIFORM | BufferUsage.COPY_DST });
  const lightData = packPunctualLights(lights);
  const lightBuffer = device.createBuffer({ label: 'raster lights', size: Math.max(64, lightData.byteLength), usage: BufferUsage.STORAGE | BufferUsage.COPY_DST });
  device.queue.writeBuffer(lightBuffer, 0, lightData);
  const shadowSize = shadowLight >= 0 && validated.shadow !== null ? validated.shadow.mapSize : 1;
  const shadowMap = device.createTexture({ label: 'raster shadow map', size: { width: shadowSize, height: shadowSize }, format: SHADOW_FORMAT, usage: TextureUsage.RENDER_ATTACHMENT | TextureUsage.TEXTURE_BINDING });
  if (shadowLight < 0) {
    // The shader never reads it; clear it once so it is initialised.
    const e = device.createCommandEncoder();
    e.beginRenderPass({ colorAttachments: [], depthStencilAttachment: { view: shadowMap.createView(), depthClearValue: 1, depthLoadOp: 'clear', depthStoreOp: 'store' } }).end();
    device.queue.submit([e.finish()]);
  }
  const frameGroupWith = (shadowView: GPUTextureView): GPUBindGroup => device.createBindGroup({
    label: 'raster frame',
    layout: pipelines.drawLayouts[0]!,
    entries: [
      { binding: 0, resource: { buffer: frameBuffer } },
      { binding: 1, resource: { buffer: lightBuffer } },
      { binding: 2, resource: shadowView },
      { binding: 3, resource: device.createSampler({ compare: 'less-equal', magFilter: 'linear', minFilter: 'linear' }) },
      { binding: 4, resource: environment.specularView },
      { binding: 5, resource: device.createSampler({ addressModeU: 'repeat', addressModeV: 'clamp-to-edge', magFilter: 'linear', minFilter: 'linear', mipmapFilter: 'linear' }) },
      { binding: 6, resource: brdfLut.createView() },
      { binding: 7, resource: device.createSampler({ magFilter: 'linear', minFilter: 'linear' }) },
      { binding: 8, resource: { buffer: environment.irradianceSh } },
    ],
  });
  const frameGroup = frameGroupWith(shadowMap.createView());
  // The shadow pass writes the map, so its frame group binds a placeholder there.
  const shadowPlaceholder = device.createTexture({ label: 'raster shadow placeholder', size: { width: 1, height: 1 }, format: SHADOW_FORMAT, usage: TextureUsage.TEXTURE_BINDING });
  const shadowPassFrameGroup = frameGroupWith(shadowPlaceholder.createView());
  const drawGroup = device.createBindGroup({ label: 'raster draw', layout: pipelines.drawLayouts[2]!, entries: [{ binding: 0, resource: { buffer: drawBuffer, size: rasterDrawLayout.size } }] });

  let width = validated.width;
  let height = validated.height;
  let attachments: { color: GPUTexture | null; depth: GPUTexture; hdr: GPUTexture; resolveGroup: GPUBindGroup } | null = null;
  const makeAttachments = (): NonNullable<typeof attachments> => {
    const usage = TextureUsage.RENDER_ATTACHMENT;
    const hdr = device.createTexture({ label: 'raster hdr', size: { width, height }, format: HDR_FORMAT, usage: usage | TextureUsage.TEXTURE_BINDING });
    const color = validated.msaa > 1 ? device.createTexture({ label: 'raster msaa colour', size: { width, height }, format: HDR_FORMAT, sampleCount: validated.msaa, usage }) : null;
    const depth = device.createTexture({ label: 'raster depth', size: { width, height }, format: DEPTH_FORMAT, sampleCount: validated.msaa, usage });
    const resolveGroup = device.createBindGroup({ layout: pipelines.resolveLayout, entries: [{ binding: 0, resource: { buffer: frameBuffer } }, { binding: 1, resource: hdr.createView() }] });
    return { color, depth, hdr, resolveGroup };
  };
  attachments = makeAttachments();
  const setupError = await device.popErrorScope();
  if (setupError) throw new GpuRendererError('GPU_VALIDATION_FAILED', `creating the raster renderer: ${setupError.message}`);

  let shadowFocus: { center: number[]; radius: number } | null = null;
  let frame = 0;
  let destroyed = false;
  const frameData = allocateStructArray(rasterFrameLayout, 1);
  const drawData = new ArrayBuffer(Math.max(1, draws.length) * DRAW_STRIDE);
  const oneDraw = allocateStructArray(rasterDrawLayout, 1);

  const worldBounds = (visibleOnly: boolean): { center: number[]; radius: number } => {
    const spheres = draws.filter((d) => !visibleOnly || d.visible).map((d) => ({ c: transformPoint(d.transform, d.streams.center), r: d.streams.radius * maxScale(d.transform) * (d.kind === 'skinned' ? 2 : 1) }));
    if (spheres.length === 0) return { center: [0, 0, 0], radius: 1 };
    const min = [Infinity, Infinity, Infinity];
    const max = [-Infinity, -Infinity, -Infinity];
    for (const s of spheres) for (let k = 0; k < 3; k++) {
      min[k] = Math.min(min[k]!, s.c[k]! - s.r);
      max[k] = Math.max(max[k]!, s.c[k]! + s.r);
    }
    const center = [0, 1, 2].map((k) => 0.5 * (min[k]! + max[k]!));
    return { center, radius: Math.max(1e-3, 0.5 * Math.hypot(max[0]! - min[0]!, max[1]! - min[1]!, max[2]! - min[2]!)) };
  };
  const defaultCamera = (): RasterCamera => {
    const b = worldBounds(false);
    const distance = b.radius / Math.sin((22.5 * Math.PI) / 180);
    return { type: 'perspective', position: [b.center[0]!, b.center[1]!, b.center[2]! + distance], target: b.center as [number, number, number], up: [0, 1, 0], fovYDegrees: 45, orthographicHeight: 2 };
  };

  const assertUsable = (): void => {
    if (destroyed) throw new GpuRendererError('RENDERER_DESTROYED', 'the raster renderer was destroyed');
  };

  const writeFrame = (): void => {
    const cam = camera ?? defaultCamera();
    const bounds = worldBounds(true);
    const viewProj = cameraViewProjection(cam, width / height, bounds.center, bounds.radius);
    const inverse = mat4.inverse(viewProj);
    let shadowViewProj = mat4.identity();
    if (shadowLight >= 0) {
      const focus = shadowFocus ?? bounds;
      shadowViewProj = lightViewProjection(lights[shadowLight]!, focus.center, focus.radius);
    }
    const values: Record<string, number | ArrayLike<number>> = {
      cameraPosition: cam.position,
      exposure: validated.exposure,
      environmentColor: uniformEnvironment ?? [0, 0, 0],
      environmentMode: environment.mode,
      environmentIntensity: environmentMap?.intensity ?? 1,
      environmentRotation: environmentMap?.rotationRadians ?? 0,
      specularMipCount: environment.specularMipCount,
      lightCount: lights.length,
      shadowLight: shadowLight >= 0 ? shadowLight : rasterConstants.SHADOW_NONE,
      shadowBias: validated.shadow?.bias ?? 0,
      shadowTexel: 1 / shadowSize,
      toneMapping: toneMappingModeIds[validated.toneMapping],
      viewportSize: [width, height],
      outputSrgb: 1,
      frameIndex: frame,
      viewDirection: towardsViewer(cam),
      orthographic: cam.type === 'orthographic' ? 1 : 0,
    };
    for (let c = 0; c < 4; c++) {
      values[`viewProj${c}`] = viewProj.subarray(4 * c, 4 * c + 4);
      values[`inverseViewProj${c}`] = inverse.subarray(4 * c, 4 * c + 4);
      values[`shadowViewProj${c}`] = shadowViewProj.subarray(4 * c, 4 * c + 4);
    }
    writeStruct(rasterFrameLayout, new DataView(frameData), 0, values);
    device.queue.writeBuffer(frameBuffer, 0, frameData);
    draws.forEach((d, i) => {
      const normal = normalMatrix(d.transform);
      const v: Record<string, number | ArrayLike<number>> = { flags: d.streams.flags, determinantSign: normal.sign, normal0: normal.columns[0]!, normal1: normal.columns[1]!, normal2: normal.columns[2]! };
      for (let c = 0; c < 4; c++) v[`model${c}`] = d.transform.subarray(4 * c, 4 * c + 4);
      if (d.kind === 'skinned') {
        const inst = skinning.instances[d.index]!;
        v.flags = d.streams.flags;
        if (inst.normals === null) v.flags = (v.flags as number) & ~rasterConstants.DRAW_HAS_NORMALS;
      }
      writeStruct(rasterDrawLayout, new DataView(oneDraw), 0, v);
      new Uint8Array(drawData, i * DRAW_STRIDE, oneDraw.byteLength).set(new Uint8Array(oneDraw));
    });
    if (draws.length > 0) device.queue.writeBuffer(drawBuffer, 0, drawData);
    return void viewProj;
  };

  const drawMesh = (pass: GPURenderPassEncoder, d: Draw, i: number, positionsOnly: boolean): void => {
    pass.setBindGroup(2, drawGroup, [i * DRAW_STRIDE]);
    const buffers = positionsOnly ? d.vertexBuffers.slice(0, 1) : d.vertexBuffers;
    buffers.forEach((b, slot) => pass.setVertexBuffer(slot, b.buffer, b.offset));
    pass.setIndexBuffer(d.streams.indexBuffer, 'uint32');
    pass.drawIndexed(d.streams.indexCount);
  };

  const renderer: RasterRenderer = {
    device,
    format,
    get width() {
      return width;
    },
    get height() {
      return height;
    },
    setCamera(input) {
      assertUsable();
      camera = validateRasterCamera(input);
    },
    setInstanceTransform(index, transform) {
      const i = requireInteger(index, 'index', { min: 0, max: scene.base.instances.length - 1 });
      draws[i]!.transform = validateTransform(transform, 'transform');
    },
    setSkinnedInstanceTransform(index, transform) {
      const i = requireInteger(index, 'index', { min: 0, max: scene.skinnedInstances.length - 1 });
      draws[scene.base.instances.length + i]!.transform = validateTransform(transform, 'transform');
    },
    setSkinPose(index, jointMatrices, morphWeights) {
      assertUsable();
      const i = requireInteger(index, 'index', { min: 0, max: scene.skinnedInstances.length - 1 });
      const inst = skinning.instances[i]!;
      if (jointMatrices.length < 16 * inst.jointCount) fail('INVALID_OPTION', 'jointMatrices', `expected ${16 * inst.jointCount} numbers (${inst.jointCount} joints), got ${jointMatrices.length}`);
      skinning.setPose(i, jointMatrices, morphWeights);
    },
    setInstanceVisible(index, visible) {
      const i = requireInteger(index, 'index', { min: 0, max: draws.length - 1 });
      draws[i]!.visible = visible;
    },
    setShadowFocus(center, radius) {
      shadowFocus = { center: [...center], radius };
    },
    resize(w, h) {
      assertUsable();
      width = requireInteger(w, 'width', { min: 1, max: device.limits.maxTextureDimension2D });
      height = requireInteger(h, 'height', { min: 1, max: device.limits.maxTextureDimension2D });
      target.setSize(width, height);
      attachments?.color?.destroy();
      attachments?.depth.destroy();
      attachments?.hdr.destroy();
      attachments = makeAttachments();
    },
    async render(): Promise<RasterFrameStats> {
      assertUsable();
      const started = performance.now();
      frame++;
      device.pushErrorScope('validation');
      writeFrame();
      const a = attachments!;
      const encoder = device.createCommandEncoder({ label: 'raster frame' });
      if (skinning.instances.length > 0) {
        const compute = encoder.beginComputePass({ label: 'raster skinning' });
        skinning.encode(compute);
        compute.end();
      }
      let drawCalls = 0;
      let triangles = 0;
      if (shadowLight >= 0) {
        const pass = encoder.beginRenderPass({ colorAttachments: [], depthStencilAttachment: { view: shadowMap.createView(), depthClearValue: 1, depthLoadOp: 'clear', depthStoreOp: 'store' } });
        pass.setPipeline(pipelines.shadow());
        pass.setBindGroup(0, shadowPassFrameGroup);
        draws.forEach((d, i) => {
          if (!d.visible || d.material.blend) return;
          pass.setBindGroup(1, d.material.bindGroup);
          drawMesh(pass, d, i, true);
          drawCalls++;
        });
        pass.end();
      }
      const colorView = (a.color ?? a.hdr).createView();
      const pass = encoder.beginRenderPass({
        colorAttachments: [{ view: colorView, ...(a.color ? { resolveTarget: a.hdr.createView() } : {}), clearValue: { r: 0, g: 0, b: 0, a: 1 }, loadOp: 'clear', storeOp: a.color ? 'discard' : 'store' }],
        depthStencilAttachment: { view: a.depth.createView(), depthClearValue: 1, depthLoadOp: 'clear', depthStoreOp: 'discard' },
      });
      pass.setBindGroup(0, frameGroup);
      const opaque: number[] = [];
      const blended: { i: number; depth: number }[] = [];
      const cam = camera ?? defaultCamera();
      draws.forEach((d, i) => {
        if (!d.visible) return;
        if (d.material.blend) {
          const c = transformPoint(d.transform, d.streams.center);
          blended.push({ i, depth: Math.hypot(c[0] - cam.position[0], c[1] - cam.position[1], c[2] - cam.position[2]) });
        } else opaque.push(i);
      });
      const submitDraw = (i: number): void => {
        const d = draws[i]!;
        pass.setPipeline(pipelines.forward({ blend: d.material.blend, doubleSided: d.material.doubleSided, mirrored: normalMatrix(d.transform).sign < 0 }));
        pass.setBindGroup(1, d.material.bindGroup);
        drawMesh(pass, d, i, false);
        drawCalls++;
        triangles += d.streams.indexCount / 3;
      };
      opaque.forEach(submitDraw);
      if (materials.length > 0) {
        pass.setPipeline(pipelines.background());
        pass.setBindGroup(1, materials[0]!.bindGroup);
        pass.setBindGroup(2, drawGroup, [0]);
        pass.draw(3);
      }
      blended.sort((x, y) => y.depth - x.depth).forEach((b) => submitDraw(b.i));
      pass.end();
      const output = encoder.beginRenderPass({ colorAttachments: [{ view: target.getCurrentTexture().createView(), loadOp: 'clear', storeOp: 'store', clearValue: { r: 0, g: 0, b: 0, a: 1 } }] });
      output.setPipeline(pipelines.resolve(format));
      output.setBindGroup(0, a.resolveGroup);
      output.draw(3);
      output.end();
      device.queue.submit([encoder.finish()]);
      const error = await device.popErrorScope();
      if (error) throw new GpuRendererError('GPU_VALIDATION_FAILED', `raster frame ${frame}: ${error.message}`);
      await device.queue.onSubmittedWorkDone();
      return { frame, frameTimeMs: performance.now() - started, drawCalls, triangles, skinnedVertices: skinning.skinnedVertexCount };
    },
    async readPixels() {
      assertUsable();
      if (target.kind !== 'offscreen') throw new GpuRendererError('INVALID_STATE', 'readPixels needs an offscreen target: presented canvas textures expire after presentation');
      return readTexturePixels(device, target.getCurrentTexture(), format);
    },
    async readSkinnedVertices(index) {
      assertUsable();
      const i = requireInteger(index, 'index', { min: 0, max: scene.skinnedInstances.length - 1 });
      const inst = skinning.instances[i]!;
      const n = inst.vertexCount;
      const ranges = [
        { offset: inst.positions, words: 3 * n },
        inst.normals === null ? null : { offset: inst.normals, words: 3 * n },
        inst.tangents === null ? null : { offset: inst.tangents, words: 4 * n },
      ];
      const out = await Promise.all(
        ranges.map(async (r) => {
          if (r === null) return null;
          const staging = device.createBuffer({ size: 4 * r.words, usage: BufferUsage.MAP_READ | BufferUsage.COPY_DST });
          const e = device.createCommandEncoder();
          e.copyBufferToBuffer(skinning.output, r.offset, staging, 0, 4 * r.words);
          device.queue.submit([e.finish()]);
          await staging.mapAsync(MapMode.READ);
          const data = new Float32Array(staging.getMappedRange().slice(0));
          staging.unmap();
          staging.destroy();
          return data;
        }),
      );
      return { positions: out[0]!, normals: out[1] ?? null, tangents: out[2] ?? null };
    },
    destroy() {
      if (destroyed) return;
      destroyed = true;
      target.release();
      for (const m of materials) m.destroy();
      for (const s of [...meshStreams, ...skinnedStreams]) s.destroy();
      skinning.destroy();
      textures.destroy();
      environment.destroy();
      brdfLut.destroy();
      shBlank.destroy();
      for (const b of [frameBuffer, drawBuffer, lightBuffer]) b.destroy();
      shadowMap.destroy();
      shadowPlaceholder.destroy();
      attachments?.color?.destroy();
      attachments?.depth.destroy();
      attachments?.hdr.destroy();
      if (ownsDevice) device.destroy();
    },
  };
  return renderer;
}
