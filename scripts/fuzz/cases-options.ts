/**
 * Renderer option sets: the Cornell box at 8 x 8 with a shared device, then one to three mutations
 * of options (boundary values, wrong types, null, unknown keys, foreign objects as the device),
 * and after a successful creation a few calls with mutated arguments (updateCamera, renderFrame,
 * readAov). Values that are valid but merely expensive (huge images, millions of samples) are left
 * out: the point is the boundary, not the GPU's speed.
 */
import { createCornellBoxScene } from '../../src/scene/cornell-box.ts';
import { BOUNDARY_VALUES, mutateJson, type Json } from './mutate-json.ts';
import type { Random } from './random.ts';

export interface OptionsCase {
  options: Record<string, unknown>;
  calls: Array<{ method: 'updateCamera' | 'renderFrame' | 'readAov' | 'renderOnce'; argument: unknown }>;
  notes: string[];
}

const CAMERAS: readonly unknown[] = [
  null,
  undefined,
  {},
  'camera',
  { position: [0, 0, 3.9], target: [0, 0, 0] },
  { position: [1e19, 0, 0], target: [0, 0, 0] },
  { position: [0, 0, 1e18], target: [0, 0, 0] },
  { position: [0, 0, 1], target: [0, 0, 1] },
  { position: [0, 0, 3], target: [0, 0, 0], up: [0, 0, 1] },
  { position: [0, 0, 3], target: [0, 0, 0], fovYDegrees: 180 },
  { position: [0, 0, 3], target: [0, 0, 0], type: 'fisheye' },
  { position: [0, 0, 3], target: [0, 0, 0], type: 'orthographic', orthographicHeight: 0 },
  { position: [NaN, 0, 3], target: [0, 0, 0] },
  { position: new Float32Array([0, 0, 3]), target: [0, 0, 0] },
  { position: [0, 0, 3], target: [0, 0, 0], extra: 1 },
];

const SPECIAL: Readonly<Record<string, readonly unknown[]>> = {
  device: [{}, null, 0, 'gpu', [], { createCommandEncoder() {} }, { createCommandEncoder() {}, createBuffer() {}, features: {}, limits: {}, queue: {} }],
  powerPreference: ['x', '', null, 0, 'low-power', 'high-performance', 'HIGH-PERFORMANCE'],
  camera: CAMERAS,
  materials: [[null], [{}], [{ baseColorFactor: [2, 2, 2] }], [{ baseColorFactor: 3 }], [{ ior: 0.5 }], [{ emissiveFactor: [1e30, 0, 0], emissiveStrength: 1e30 }], [{ unknown: 1 }], null, {}],
  meshes: [[null], [], [{}], [{ positions: [0, 0, 0, 1, 0, 0, 0, 1, 0], material: null }], [{ positions: [1e19, 0, 0, 1, 0, 0, 0, 1, 0] }], [{ positions: new Float32Array(9), indices: [0, 1, 5] }]],
  instances: [[null], [{ mesh: 99 }], [{ mesh: 0, transform: [0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1] }], [{ mesh: 0, material: -1 }]],
  lights: [[null], [{ type: 'point', position: [0, 0, 0], intensity: -1 }], [{ type: 'laser' }], [{ type: 'spot', position: [0, 0, 0], direction: [0, 0, 0] }], [{ type: 'rectangle', position: [0, 0, 0] }], {}],
  environmentMap: [null, {}, { width: 1e9, height: 1, data: new Float32Array(4) }, { width: 2, height: 1, data: new Float32Array(8).fill(-1) }, { width: 2, height: 1, data: [1, 1, 1, 1, 1, 1, 1, 1] }, { width: 2, height: 1, data: new Float32Array(8).fill(1), intensity: NaN }],
  environment: [null, { color: [1, 1, 1] }, { color: [-1, 0, 0] }, { color: [1e21, 0, 0] }, { map: 'sky.hdr' }],
  images: [[null], [{ width: 1e9, height: 1e9, data: new Uint8Array(4) }], [{ width: 1, height: 1, data: [256, 0, 0, 0] }]],
  textures: [[null], [{ image: 5 }], [{ image: 0, sampler: { wrapS: 'spiral' } }]],
  sceneObjects: [[null], [{ type: 'sphere', center: [0, 0, 0], radius: -1 }], [{ type: 'torus' }]],
  canvas: ['#missing', {}, 5, null],
  width: [0, -1, 1.5, 16385, 1e9, NaN, '8', null, 1, 3],
  height: [0, -1, 1.5, 16385, 1e9, NaN, '8', null, 1, 3],
  samplesPerPixel: [0, -1, 1.5, 65537, '1', null, 2],
  maxDepth: [0, 33, -1, 1.5, null, 1, 32],
  tileSize: [0, 7, 1025, 8.5, null, 8],
  seed: [-1, 2 ** 32, 1.5, null, 0],
  toneMapping: ['reinhard', '', null, 'agx', 'linear'],
  exposure: [-1, NaN, Infinity, 1e30, null, 0],
  aovs: ['yes', 1, null, true],
  denoise: ['yes', 1, null, true, {}],
  adaptiveThreshold: [-1, 0, NaN, 'x', null, 0.05],
  shaderSpecialization: ['none', null, 'scene'],
  energyCompensation: ['no', 0, null, false],
  onProgress: [5, 'x', {}],
  environmentPortals: [[null], [{}], 'portal'],
  lightSampler: ['random', null, {}, 'power'],
};

const FRAME_OPTIONS: readonly unknown[] = [
  undefined, null, 5, 'x', {}, { samplesPerPixel: 0 }, { samplesPerPixel: -1 }, { samplesPerPixel: 1.5 }, { samplesPerPixel: 2 }, { samplesPerPixel: 70000 },
  { frameTimeBudgetMs: -1 }, { frameTimeBudgetMs: NaN }, { frameTimeBudgetMs: 5 }, { minimumSamplesPerPixel: -1 }, { unknown: true }, { onProgress: 3 },
];

const AOV_NAMES: readonly unknown[] = ['albedo', 'normal', 'depth', 'variance', 'sampleCount', 'beauty', '', null, 5, {}, '__proto__'];

export function makeOptionsCase(random: Random): OptionsCase {
  const base = { ...createCornellBoxScene(), width: 8, height: 8, samplesPerPixel: 1, maxDepth: 2 } as unknown as Record<string, Json>;
  let options: Record<string, unknown> = base;
  const notes: string[] = [];
  // A third of the sets stay valid, so that the calls after creation are reached.
  const rounds = random.chance(0.33) ? 0 : 1 + (random.chance(0.5) ? 0 : random.int(3));
  for (let r = 0; r < rounds; r++) {
    if (random.chance(0.35)) {
      const m = mutateJson(options as Json, random);
      if (m.value === null || typeof m.value !== 'object' || Array.isArray(m.value)) continue;
      options = m.value as Record<string, unknown>;
      notes.push(m.note);
    } else {
      const key = random.chance(0.05) ? random.pick(['unknownOption', 'constructor', 'toString']) : random.pick(Object.keys(SPECIAL));
      const pool = SPECIAL[key] ?? BOUNDARY_VALUES;
      const value = random.chance(0.85) ? random.pick(pool) : random.pick(BOUNDARY_VALUES);
      options = { ...options, [key]: value };
      notes.push(`${key} = ${describeValue(value)}`);
    }
  }
  const calls: OptionsCase['calls'] = [];
  const callCount = rounds === 0 ? 1 + random.int(4) : random.int(4);
  for (let c = 0; c < callCount; c++) {
    const method = random.pick(['updateCamera', 'renderFrame', 'readAov', 'renderOnce'] as const);
    const argument = method === 'updateCamera' ? random.pick(CAMERAS) : method === 'readAov' ? random.pick(AOV_NAMES) : random.pick(FRAME_OPTIONS);
    calls.push({ method, argument });
    notes.push(`${method}(${describeValue(argument)})`);
  }
  return { options, calls, notes };
}

function describeValue(value: unknown): string {
  if (typeof value === 'function') return 'a function';
  if (ArrayBuffer.isView(value)) return `a ${value.constructor.name}`;
  try {
    return (JSON.stringify(value, (_k, v: unknown) => (typeof v === 'function' ? '[function]' : ArrayBuffer.isView(v) ? `[${v.constructor.name}]` : v)) ?? String(value)).slice(0, 80);
  } catch {
    return String(value);
  }
}
