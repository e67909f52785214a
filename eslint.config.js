// ESLint 10 flat config. typescript-eslint parses with the TypeScript 6 API (TypeScript 7 ships no
// JS API yet); type checking itself is done by TypeScript 7 in `npm run typecheck`.
import js from '@eslint/js';
import tseslint from 'typescript-eslint';

export default tseslint.config(
  { ignores: ['dist/**', 'node_modules/**', 'coverage/**', 'out/**', 'src/shaders/programs.generated.ts', 'src/shaders/program-sources.generated.ts', 'src/shaders/wgsl/**', 'src/io/gltf/codecs/*.generated.ts', 'weights/**/*.js'] },
  js.configs.recommended,
  ...tseslint.configs.recommended,
  {
    languageOptions: {
      ecmaVersion: 2023,
      sourceType: 'module',
      globals: {
        console: 'readonly', process: 'readonly', navigator: 'readonly', document: 'readonly',
        window: 'readonly', globalThis: 'readonly', performance: 'readonly', setTimeout: 'readonly',
        clearTimeout: 'readonly', queueMicrotask: 'readonly', URL: 'readonly', Buffer: 'readonly',
        GPUBufferUsage: 'readonly', GPUShaderStage: 'readonly', GPUMapMode: 'readonly',
        GPUTextureUsage: 'readonly', OffscreenCanvas: 'readonly', HTMLCanvasElement: 'readonly',
        requestAnimationFrame: 'readonly', cancelAnimationFrame: 'readonly', MessageChannel: 'readonly',
      },
    },
    rules: {
      '@typescript-eslint/no-unused-vars': ['error', { argsIgnorePattern: '^_', varsIgnorePattern: '^_' }],
      '@typescript-eslint/consistent-type-imports': 'error',
      'no-constant-condition': ['error', { checkLoops: false }],
    },
  },
);
