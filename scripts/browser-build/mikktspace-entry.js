/* global WebAssembly, atob */
// `mikktspace` in the browser build (bundled by vendor.ts into dist/browser/vendor/mikktspace.js):
// the package's own wasm-bindgen glue (`mikktspace-glue`, its bundler build) around the
// WebAssembly of its Node.js build, inlined as base64 (`mikktspace-wasm`), so no bundler has to
// load a .wasm file. Browsers compile modules over 4 KiB only asynchronously on the main thread,
// hence `ready()`, which src/io/gltf/tangents.ts awaits before the first `generateTangents` call.
import * as glue from 'mikktspace-glue';
import { bindWasmExports, wasmBase64 } from 'mikktspace-wasm';

export { generateTangents } from 'mikktspace-glue';

let instantiation;

function decodeBase64(text) {
  const binary = atob(text);
  const bytes = new Uint8Array(binary.length);
  for (let i = 0; i < binary.length; i++) bytes[i] = binary.charCodeAt(i);
  return bytes;
}

async function instantiate() {
  const module = await WebAssembly.compile(decodeBase64(wasmBase64));
  // The glue provides every import, under whichever module name the binary declares.
  const imports = {};
  for (const { module: name } of WebAssembly.Module.imports(module)) imports[name] = glue;
  const instance = await WebAssembly.instantiate(module, imports);
  bindWasmExports(instance.exports);
}

/** Compiles and instantiates the WebAssembly (once); `generateTangents` works after it resolves. */
export function ready() {
  instantiation ??= instantiate();
  return instantiation;
}
