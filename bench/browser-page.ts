/**
 * What the browser bench (bench/browser.ts) runs inside the page, through Playwright's
 * `evaluate`: each function is serialized on its own, so it imports what it needs itself (the page's
 * import map resolves three, three-mesh-bvh and three-gpu-pathtracer; `window.pkg` is our
 * package) and closes over nothing.
 *
 * Both renderers are timed the same way: warm-up (shader compilation: one frame of ours, the peer's calls
 * until its first sample completes), a reset, then calls
 * until the budget is spent, each waited on until the GPU finishes it; the loop stops when the next
 * call would end further past the budget than stopping now ends short of it, so both spend the
 * budget within half a call. Both return linear radiance (no tone mapping), RGB, row 0 at the top.
 */
import type { BenchScene } from './browser-scenes.ts';
import type * as Pkg from '../src/index.ts';

export interface PageRun {
  renderer: string;
  adapter: string;
  /** Mean samples per pixel accumulated in the timed calls. */
  spp: number;
  seconds: number;
  calls: number;
  warmupSeconds: number;
  rgb: number[];
}

export interface PageArgs {
  scene: BenchScene;
  ourOptions: Record<string, unknown>;
  width: number;
  height: number;
  seconds: number;
  /** For ours: 0 = the seed of the timed runs. */
  seed: number;
}

/** GPUAdapterInfo of the page's default adapter, as one line. */
export async function pageAdapterInfo(): Promise<string> {
  const adapter = await navigator.gpu.requestAdapter();
  if (!adapter) return 'no WebGPU adapter';
  const i = adapter.info;
  return [i.vendor, i.architecture, i.device, i.description].filter((s) => s).join(' / ') || 'adapter without info';
}

/** Our wavefront path tracer: 1 spp per renderFrame. */
export async function runOurs(args: PageArgs): Promise<PageRun> {
  const { createWavefrontPathTracingComputeRenderer } = (window as unknown as { pkg: typeof Pkg }).pkg;
  const { width, height, seconds } = args;
  const t0 = performance.now();
  const renderer = await createWavefrontPathTracingComputeRenderer({ ...args.ourOptions, width, height, seed: args.seed, toneMapping: 'linear', samplesPerPixel: 1 } as unknown as Parameters<typeof createWavefrontPathTracingComputeRenderer>[0]);
  try {
    await renderer.renderFrame();
    // updateCamera restarts the accumulation (the warm-up sample is dropped).
    renderer.updateCamera(args.ourOptions.camera as Parameters<typeof renderer.updateCamera>[0]);
    const warmupSeconds = (performance.now() - t0) / 1000;
    const start = performance.now();
    let calls = 0;
    let last = 0;
    let spp = 0;
    for (;;) {
      const elapsed = (performance.now() - start) / 1000;
      if (calls > 0 && elapsed + last / 2 >= seconds) break;
      const c0 = performance.now();
      const stats = await renderer.renderFrame({ samplesPerPixel: 1 });
      last = (performance.now() - c0) / 1000;
      spp = stats.samplesAccumulated;
      calls++;
    }
    const elapsed = (performance.now() - start) / 1000;
    const image = await renderer.readRadiance();
    const rgb: number[] = new Array<number>(width * height * 3);
    for (let i = 0; i < width * height; i++) for (let k = 0; k < 3; k++) rgb[3 * i + k] = image.data[4 * i + k]!;
    return { renderer: 'ours', adapter: renderer.getSnapshot().adapter, spp, seconds: elapsed, calls, warmupSeconds, rgb };
  } finally {
    renderer.destroy();
  }
}

/**
 * three-gpu-pathtracer's WebGPUPathTracer (wavefront backend), built from the same scene data:
 * MeshPhysicalMaterial (Lambertian: ior 1 and specularIntensity 0, so no dielectric lobe; metals:
 * metalness 1), RectAreaLight (NEE with MIS), the uniform environment as an equirect float texture
 * in half floats (also the background, as our camera rays see the environment). Its defaults that bias or blur
 * (glossy filter, indirect clamp, low-resolution preview) are off.
 */
export async function runPeer(args: PageArgs & { frameBudget: number }): Promise<PageRun> {
  const THREE = await import('three/webgpu');
  const { WebGPUPathTracer } = await import('three-gpu-pathtracer/webgpu');
  const { scene: spec, width, height, seconds } = args;
  const t0 = performance.now();
  const renderer = new THREE.WebGPURenderer({ antialias: false });
  renderer.setPixelRatio(1);
  renderer.setSize(width, height);
  renderer.toneMapping = THREE.NoToneMapping;
  renderer.setClearColor(0x000000, 1);
  await renderer.init();
  document.body.appendChild(renderer.domElement);

  const scene = new THREE.Scene();
  for (const m of spec.meshes) {
    let geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.Float32BufferAttribute(m.positions, 3));
    geometry.setIndex(m.indices);
    if (m.normals) {
      geometry.setAttribute('normal', new THREE.Float32BufferAttribute(m.normals, 3));
    } else {
      // Flat shading as ours does without normals: unshared vertices, face normals.
      geometry = geometry.toNonIndexed();
      geometry.computeVertexNormals();
    }
    const [r, g, b] = m.material.baseColor;
    const material = new THREE.MeshPhysicalMaterial({
      color: new THREE.Color(r, g, b),
      metalness: m.material.metallic,
      roughness: m.material.roughness,
      ...(m.material.metallic === 0 ? { ior: 1, specularIntensity: 0 } : {}),
    });
    scene.add(new THREE.Mesh(geometry, material));
  }
  for (const l of spec.rectLights) {
    // three-gpu-pathtracer's rectangle spans width along local x and height along local y and lights the
    // side opposite cross(x, y) (local -z); ours lights the side cross(edgeU, edgeV) faces. So x = edgeU,
    // y = -edgeV.
    const len = (v: number[]) => Math.hypot(v[0]!, v[1]!, v[2]!);
    const x = new THREE.Vector3(...l.edgeU).normalize();
    const y = new THREE.Vector3(...l.edgeV).normalize().negate();
    const z = new THREE.Vector3().crossVectors(x, y);
    const light = new THREE.RectAreaLight(new THREE.Color(...l.radiance), 1, len(l.edgeU), len(l.edgeV));
    light.position.set(...l.center);
    light.quaternion.setFromRotationMatrix(new THREE.Matrix4().makeBasis(x, y, z));
    scene.add(light);
  }
  if (spec.environment) {
    const [w, h] = [64, 32];
    // Half floats: float32 textures are not filterable on every adapter (SwiftShader), and the peer samples
    // its environment with a filtering sampler. The scenes' environment values are exact in half precision.
    const data = new Uint16Array(w * h * 4);
    const texel = [...spec.environment, 1].map((v) => THREE.DataUtils.toHalfFloat(v));
    for (let i = 0; i < w * h; i++) data.set(texel, 4 * i);
    const env = new THREE.DataTexture(data, w, h, THREE.RGBAFormat, THREE.HalfFloatType);
    env.mapping = THREE.EquirectangularReflectionMapping;
    // Linear filtering as an HDR loader's texture has (a nearest-filtered DataTexture gets no sampler in the peer's kernels).
    env.minFilter = THREE.LinearFilter;
    env.magFilter = THREE.LinearFilter;
    env.colorSpace = THREE.LinearSRGBColorSpace;
    env.needsUpdate = true;
    scene.environment = env;
    scene.background = env;
  } else {
    scene.environmentIntensity = 0;
  }
  const camera = new THREE.PerspectiveCamera(spec.camera.fovYDegrees, width / height, 0.01, 100);
  camera.position.set(...spec.camera.position);
  camera.lookAt(new THREE.Vector3(...spec.camera.target));
  camera.updateMatrixWorld();

  const pathTracer = new WebGPUPathTracer(renderer);
  pathTracer.synchronizeRenderSize = false;
  pathTracer.setSize(width, height);
  pathTracer.renderDelay = 0;
  pathTracer.dynamicLowRes = false;
  pathTracer.minSamples = 0;
  pathTracer.fadeDuration = 0;
  pathTracer.filterGlossyFactor = 0;
  pathTracer.clampIndirect = 0;
  pathTracer.clampDirect = 0;
  pathTracer.maxBounces = spec.maxDepth;
  pathTracer.frameBudget = args.frameBudget;
  pathTracer.setScene(scene, camera);
  const device = (renderer.backend as unknown as { device: GPUDevice }).device;
  const call = async (): Promise<void> => {
    pathTracer.renderSample();
    await device.queue.onSubmittedWorkDone();
  };
  try {
    // Warm up until a first sample has completed, so every kernel the paths reach has been compiled.
    for (let i = 0; i < 4 * spec.maxDepth + 16; i++) {
      await call();
      if ((await pathTracer.getSampleCountsAsync()).avg > 0) break;
    }
    pathTracer.reset();
    const warmupSeconds = (performance.now() - t0) / 1000;
    const start = performance.now();
    let calls = 0;
    let last = 0;
    for (;;) {
      const elapsed = (performance.now() - start) / 1000;
      if (calls > 0 && elapsed + last / 2 >= seconds) break;
      const c0 = performance.now();
      await call();
      last = (performance.now() - c0) / 1000;
      calls++;
    }
    const elapsed = (performance.now() - start) / 1000;
    const counts = await pathTracer.getSampleCountsAsync();
    const target = pathTracer.target!;
    const backend = renderer.backend as unknown as { copyTextureToBuffer(t: unknown, x: number, y: number, w: number, h: number, face: number): Promise<Float32Array> };
    const data = await backend.copyTextureToBuffer(target, 0, 0, width, height, 0);
    const rgb: number[] = new Array<number>(width * height * 3);
    // Row 0 is the top row, as in ours (checked on the Cornell box: the lit floor is at the bottom).
    for (let i = 0; i < width * height; i++) for (let k = 0; k < 3; k++) rgb[3 * i + k] = data[4 * i + k]!;
    const info = (device as GPUDevice & { adapterInfo?: GPUAdapterInfo }).adapterInfo;
    const adapter = info ? [info.vendor, info.architecture, info.device, info.description].filter((s) => s).join(' / ') : 'unknown';
    return { renderer: 'three-gpu-pathtracer', adapter, spp: counts.avg, seconds: elapsed, calls, warmupSeconds, rgb };
  } finally {
    pathTracer.dispose();
    renderer.dispose();
    renderer.domElement.remove();
  }
}
