/**
 * Independent decoders for the file tests: three.js's EXRLoader and HDRLoader (maintained readers
 * that share no code with ours), and the reference OpenEXR library through its official Python
 * bindings when they are installed.
 */
import { spawnSync } from 'node:child_process';
import { fileURLToPath } from 'node:url';
import { FloatType } from 'three';
import { EXRLoader } from 'three/examples/jsm/loaders/EXRLoader.js';
import { HDRLoader } from 'three/examples/jsm/loaders/HDRLoader.js';

export interface DecodedRgba {
  width: number;
  height: number;
  /** RGBA float, top row first. */
  data: Float32Array;
  header: Record<string, unknown>;
}

const toArrayBuffer = (bytes: Uint8Array): ArrayBuffer => bytes.slice().buffer as ArrayBuffer;

/** three's EXRLoader decodes R, G, B, A (bottom row first, as textures are); flipped back here. */
export function readExrWithThree(bytes: Uint8Array): DecodedRgba {
  const loader = new EXRLoader().setDataType(FloatType);
  const result = loader.parse(toArrayBuffer(bytes)) as { width: number; height: number; data: Float32Array; header: Record<string, unknown> };
  const { width, height, data } = result;
  const topFirst = new Float32Array(data.length);
  for (let y = 0; y < height; y++) topFirst.set(data.subarray((height - 1 - y) * width * 4, (height - y) * width * 4), y * width * 4);
  return { width, height, data: topFirst, header: result.header };
}

/** three's HDRLoader (the RGBELoader successor); its rows come out top first. */
export function readHdrWithThree(bytes: Uint8Array): DecodedRgba {
  const loader = new HDRLoader().setDataType(FloatType);
  const result = loader.parse(toArrayBuffer(bytes)) as { width: number; height: number; data: Float32Array; header: string };
  return { width: result.width, height: result.height, data: result.data, header: { text: result.header } };
}

export interface OpenExrDump {
  header: Record<string, unknown>;
  channels: Record<string, { type: string; shape: number[]; values: number[] }>;
}

const dumpScript = fileURLToPath(new URL('./openexr-dump.py', import.meta.url));
const python = process.env.GPU_RENDERER_OPENEXR_PYTHON ?? 'python3';

/** Why the OpenEXR cross-check cannot run here, or undefined when it can. */
export function openExrUnavailable(): string | undefined {
  const probe = spawnSync(python, ['-c', 'import OpenEXR'], { encoding: 'utf8' });
  if (probe.error || probe.status !== 0) {
    return `no Python with the OpenEXR bindings (pip install openexr; set GPU_RENDERER_OPENEXR_PYTHON to that python)`;
  }
  return undefined;
}

export function readExrWithOpenExr(path: string): OpenExrDump {
  const run = spawnSync(python, [dumpScript, path], { encoding: 'utf8', maxBuffer: 64 * 1024 * 1024 });
  if (run.status !== 0) throw new Error(`OpenEXR could not read ${path}: ${run.stderr}`);
  return JSON.parse(run.stdout) as OpenExrDump;
}
