// Vite configuration of the demo page (`npm run demo`, or `npx vite demo`). The page imports the
// package by its published name; the alias points that name at the TypeScript sources, so the demo
// always shows the current code (Vite compiles the .ts on request, no build step).
import { fileURLToPath } from 'node:url';
import { defineConfig, type UserConfig } from 'vite';

const demoRoot = fileURLToPath(new URL('.', import.meta.url));
const repoRoot = fileURLToPath(new URL('..', import.meta.url));

export const demoViteConfig: UserConfig = {
  root: demoRoot,
  clearScreen: false,
  resolve: {
    alias: { '@plasius/gpu-renderer': fileURLToPath(new URL('../src/index.ts', import.meta.url)) },
  },
  server: {
    host: '127.0.0.1',
    // The sources live beside demo/, not under it.
    fs: { allow: [repoRoot] },
    // Cross-origin isolation gives the page SharedArrayBuffer, so large glTF assets build their BVH
    // on parallel workers (see the README's note on COOP/COEP).
    headers: { 'Cross-Origin-Opener-Policy': 'same-origin', 'Cross-Origin-Embedder-Policy': 'require-corp' },
  },
  preview: {
    headers: { 'Cross-Origin-Opener-Policy': 'same-origin', 'Cross-Origin-Embedder-Policy': 'require-corp' },
  },
  optimizeDeps: {
    // Pre-bundle every browser-side dependency up front: discovering one on first use makes Vite
    // reload the page mid-session.
    entries: ['index.html'],
    // The HDRI maps (@pmndrs/assets) and three's EXRLoader are dynamic imports: each stays a chunk of
    // its own, fetched when the environment picker first needs it.
    include: [
      '@gltf-transform/core',
      '@gltf-transform/extensions',
      'fflate',
      'fast-png',
      'jpeg-js',
      'meshoptimizer',
      'mikktspace',
      'wgpu-matrix',
      'three/examples/jsm/loaders/EXRLoader.js',
      '@pmndrs/assets/hdri/studio.exr.js',
      '@pmndrs/assets/hdri/city.exr.js',
      '@pmndrs/assets/hdri/sunset.exr.js',
    ],
  },
  build: { target: 'es2022', outDir: fileURLToPath(new URL('../dist-demo', import.meta.url)), emptyOutDir: true },
};

export default defineConfig(demoViteConfig);
