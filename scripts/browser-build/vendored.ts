// The dependencies the browser build carries inside itself, and the file each becomes. Everything
// else the package imports stays a bare import that the consumer's bundler resolves (and shares
// with the rest of the application).
// - @gltf-transform/core's one module imports node:fs and node:path (for NodeIO), which esbuild
//   and webpack refuse when bundling for browsers; the copy here has them stubbed out.
// - @gltf-transform/extensions imports core, so it has to import that copy.
// - mikktspace imports its .wasm as an ES module (wasm-bindgen's "bundler" target), which only
//   webpack with experiments.asyncWebAssembly bundles; the copy here inlines the bytes.
export const vendoredModules: Readonly<Record<string, string>> = {
  '@gltf-transform/core': 'vendor/gltf-transform-core.js',
  '@gltf-transform/extensions': 'vendor/gltf-transform-extensions.js',
  mikktspace: 'vendor/mikktspace.js',
};

/** The notices file for everything vendored (the MIT licences ask for their text in copies). */
export const noticesFile = 'vendor/THIRD-PARTY-NOTICES.txt';
