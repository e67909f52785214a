// A throwaway Redis for the farm tests: Debian's redis-server (scripts/setup.sh installs it) on a
// free loopback port, without persistence, stopped (by its pid) when the test ends. Optionally with
// a password (`requirepass`) and/or TLS only (`--port 0 --tls-port`), its self-signed certificate
// made by openssl at start (for 127.0.0.1; clients trust it through NODE_EXTRA_CA_CERTS=caFile).
import { spawn, spawnSync, type ChildProcess } from 'node:child_process';
import { mkdtemp, rm } from 'node:fs/promises';
import { createServer, connect, type Socket } from 'node:net';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { connect as connectTls } from 'node:tls';

export interface LocalRedis {
  /** redis://127.0.0.1:port, or rediss://... with TLS; with a password, redis://:password@... */
  url: string;
  port: number;
  /** With TLS: the server's self-signed certificate, the CA a client must trust. */
  caFile?: string;
  stop(): Promise<void>;
}

export interface RedisStartOptions {
  /** requirepass: clients must AUTH with it. */
  password?: string;
  /** Serve TLS only, with a self-signed certificate for 127.0.0.1. */
  tls?: boolean;
}

/** A loopback TCP port nothing listens on now. */
export function freePort(): Promise<number> {
  return new Promise((resolve, reject) => {
    const server = createServer();
    server.on('error', reject);
    server.listen(0, '127.0.0.1', () => {
      const address = server.address();
      const port = typeof address === 'object' && address !== null ? address.port : 0;
      server.close(() => resolve(port));
    });
  });
}

/** Whether a Redis answers on `port` (a PONG, or NOAUTH from one that wants a password). */
function answersPing(port: number, tls: boolean): Promise<boolean> {
  return new Promise((resolve) => {
    const socket: Socket = tls ? connectTls({ port, host: '127.0.0.1', rejectUnauthorized: false }) : connect(port, '127.0.0.1');
    socket.setTimeout(500);
    socket.on(tls ? 'secureConnect' : 'connect', () => socket.write('PING\r\n'));
    socket.on('data', (data) => {
      socket.destroy();
      resolve(data.toString().startsWith('+PONG') || data.toString().startsWith('-NOAUTH'));
    });
    socket.on('error', () => resolve(false));
    socket.on('timeout', () => {
      socket.destroy();
      resolve(false);
    });
  });
}

export function hasRedisServer(): boolean {
  return spawnSync('redis-server', ['--version'], { stdio: 'ignore' }).status === 0;
}

export function hasOpenssl(): boolean {
  return spawnSync('openssl', ['version'], { stdio: 'ignore' }).status === 0;
}

/**
 * Why this machine cannot run a TLS Redis (no openssl, or a redis-server built without TLS, which
 * refuses --tls-port), or undefined when it can.
 */
export function redisTlsUnsupported(): string | undefined {
  if (!hasRedisServer()) return 'redis-server is not installed (npm run setup)';
  if (!hasOpenssl()) return 'openssl is not installed (npm run setup)';
  // Config is read in order and stops at the first bad directive: a build without TLS stops at
  // tls-port, one with TLS at the made-up directive after it.
  const probe = spawnSync('redis-server', ['--port', '0', '--tls-port', '0', '--gpu-renderer-probe', '1'], { encoding: 'utf8', timeout: 5000 });
  const said = `${probe.stdout}${probe.stderr}`;
  if (!said.includes('gpu-renderer-probe')) return `redis-server ${spawnSync('redis-server', ['--version'], { encoding: 'utf8' }).stdout.trim()} was built without TLS (it refuses --tls-port)`;
  return undefined;
}

/** A self-signed certificate for 127.0.0.1 (and localhost) in `dir`: openssl req -x509. */
function makeCertificate(dir: string): { cert: string; key: string } {
  const cert = join(dir, 'redis.crt');
  const key = join(dir, 'redis.key');
  const made = spawnSync('openssl', ['req', '-x509', '-newkey', 'rsa:2048', '-nodes', '-keyout', key, '-out', cert, '-days', '1', '-subj', '/CN=127.0.0.1', '-addext', 'subjectAltName=IP:127.0.0.1,DNS:localhost'], { encoding: 'utf8' });
  if (made.status !== 0) throw new Error(`openssl could not make a certificate: ${made.stderr}`);
  return { cert, key };
}

export async function startRedis(options: RedisStartOptions = {}): Promise<LocalRedis> {
  if (!hasRedisServer()) throw new Error('redis-server is not installed: run `npm run setup` (Debian package redis-server)');
  const port = await freePort();
  const dir = options.tls ? await mkdtemp(join(tmpdir(), 'gpu-renderer-redis-tls-')) : undefined;
  const args = ['--bind', '127.0.0.1', '--save', '', '--appendonly', 'no', '--protected-mode', 'yes'];
  let caFile: string | undefined;
  if (dir !== undefined) {
    const { cert, key } = makeCertificate(dir);
    caFile = cert;
    args.push('--port', '0', '--tls-port', String(port), '--tls-cert-file', cert, '--tls-key-file', key, '--tls-auth-clients', 'no');
  } else {
    args.push('--port', String(port));
  }
  if (options.password !== undefined) args.push('--requirepass', options.password);
  const child: ChildProcess = spawn('redis-server', args, { stdio: 'ignore' });
  const exited = new Promise<void>((resolve) => child.on('exit', () => resolve()));
  const deadline = Date.now() + 10_000;
  while (!(await answersPing(port, dir !== undefined))) {
    if (child.exitCode !== null || Date.now() > deadline) {
      child.kill('SIGKILL');
      throw new Error(`redis-server did not start on port ${port}`);
    }
    await new Promise((r) => setTimeout(r, 50));
  }
  const auth = options.password !== undefined ? `:${encodeURIComponent(options.password)}@` : '';
  return {
    url: `${dir !== undefined ? 'rediss' : 'redis'}://${auth}127.0.0.1:${port}`,
    port,
    ...(caFile !== undefined ? { caFile } : {}),
    stop: async () => {
      if (child.exitCode === null) child.kill('SIGTERM');
      await exited;
      if (dir !== undefined) await rm(dir, { recursive: true, force: true });
    },
  };
}
