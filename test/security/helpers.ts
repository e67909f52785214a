// Fixtures for hostile-input tests: an asset folder beside a canary file whose access time shows
// whether anything read it, local HTTP servers that record every request, and a tiny glTF.
import assert from 'node:assert/strict';
import { mkdirSync, mkdtempSync, rmSync, statSync, utimesSync, writeFileSync } from 'node:fs';
import { createServer, type IncomingMessage, type ServerResponse } from 'node:http';
import type { AddressInfo } from 'node:net';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { GpuRendererError } from '../../src/errors/gpu-renderer-error.ts';

const ARMED = new Date('2001-01-01T00:00:00Z');

/**
 * `root/asset/` (the asset folder) and `root/canary.bin` outside it. The canary's access time is set
 * before its modification time, so (Linux relatime) its first read moves it: `canaryRead()` says
 * whether anything read the file since.
 */
export function assetFolder(): { root: string; asset: string; canary: string; canaryRead: () => boolean; cleanup: () => void } {
  const root = mkdtempSync(join(tmpdir(), 'hostile-'));
  const asset = join(root, 'asset');
  mkdirSync(join(asset, 'sub'), { recursive: true });
  const canary = join(root, 'canary.bin');
  writeFileSync(canary, new Uint8Array(64).fill(0x42));
  utimesSync(canary, ARMED, new Date());
  return {
    root,
    asset,
    canary,
    canaryRead: () => statSync(canary).atimeMs !== ARMED.getTime(),
    cleanup: () => rmSync(root, { recursive: true, force: true }),
  };
}

/** 36 bytes: one triangle's float32 positions. */
export const TRIANGLE = new Uint8Array(new Float32Array([0, 0, 0, 1, 0, 0, 0, 1, 0]).buffer);

/** A one-triangle glTF whose buffer is named by `uri` (36 bytes expected). */
export function triangleGltf(uri: string, extra: Record<string, unknown> = {}): Record<string, unknown> {
  return {
    asset: { version: '2.0' },
    buffers: [{ uri, byteLength: 36 }],
    bufferViews: [{ buffer: 0, byteLength: 36 }],
    accessors: [{ bufferView: 0, componentType: 5126, count: 3, type: 'VEC3', min: [0, 0, 0], max: [1, 1, 0] }],
    meshes: [{ primitives: [{ attributes: { POSITION: 0 } }] }],
    nodes: [{ mesh: 0 }],
    scenes: [{ nodes: [0] }],
    ...extra,
  };
}

export const triangleDataUri = `data:application/octet-stream;base64,${Buffer.from(TRIANGLE).toString('base64')}`;

export interface RecordingServer {
  origin: string;
  requests: string[];
  close: () => void;
}

/** A local server recording every request path; `route` answers (default: 404). */
export async function recordingServer(route: (req: IncomingMessage, res: ServerResponse) => boolean = () => false): Promise<RecordingServer> {
  const requests: string[] = [];
  const server = createServer((req, res) => {
    requests.push(req.url ?? '');
    if (!route(req, res)) {
      res.statusCode = 404;
      res.end();
    }
  });
  await new Promise<void>((resolve) => server.listen(0, '127.0.0.1', resolve));
  const { port } = server.address() as AddressInfo;
  return {
    origin: `http://127.0.0.1:${port}`,
    requests,
    close: () => {
      server.closeAllConnections();
      server.close();
    },
  };
}

/** Asserts a typed error of `code` at `field` (and `message`), within `maxMs`. */
export async function refused(promise: Promise<unknown>, code: string, field: string | RegExp, message?: RegExp, maxMs = 10_000): Promise<GpuRendererError> {
  const started = performance.now();
  let caught: unknown;
  try {
    await promise;
  } catch (error) {
    caught = error;
  }
  const ms = performance.now() - started;
  assert.ok(caught instanceof GpuRendererError, `expected a GpuRendererError, got ${caught === undefined ? 'success' : String((caught as Error)?.stack ?? caught)}`);
  assert.equal(caught.code, code, caught.message);
  if (typeof field === 'string') assert.equal(caught.field, field, caught.message);
  else assert.match(caught.field ?? '', field, caught.message);
  if (message) assert.match(caught.message, message);
  assert.ok(ms < maxMs, `took ${ms.toFixed(0)} ms (limit ${maxMs})`);
  return caught;
}
