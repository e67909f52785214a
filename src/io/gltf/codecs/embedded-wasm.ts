/** WebAssembly embedded in generated modules (scripts/codec-build): zlib-deflated, base64-encoded. */
import { unzlibSync } from 'fflate';

/** Decodes and compiles an embedded module. */
export async function compileEmbeddedWasm(base64: string): Promise<WebAssembly.Module> {
  const text = atob(base64);
  const deflated = new Uint8Array(text.length);
  for (let i = 0; i < text.length; i++) deflated[i] = text.charCodeAt(i);
  return WebAssembly.compile(unzlibSync(deflated));
}

/** Emscripten's `instantiateWasm` hook for a module compiled here. */
export function instantiateWith(module: WebAssembly.Module): (imports: WebAssembly.Imports, receive: (instance: WebAssembly.Instance) => void) => object {
  return (imports, receive) => {
    void WebAssembly.instantiate(module, imports).then(receive);
    return {};
  };
}
