import { createWgslModuleRegistry, composeWgsl, type WgslModule, type WgslModuleRegistry } from './compose.ts';
import { createRecordsWgsl } from './records-module.ts';
import { wgslSources } from './wgsl-sources.generated.ts';

function fromFile(name: string, requires: readonly string[]): WgslModule {
  const source = wgslSources[name];
  if (source === undefined) throw new Error(`missing WGSL source file src/shaders/wgsl/${name}.wgsl`);
  return { name, requires, source };
}

/**
 * Every WGSL module of the renderer and what it requires. Kernels are entry modules; a pipeline's
 * shader is `composeWgsl(registry, [kernel])`.
 */
export function createShaderModuleRegistry(): WgslModuleRegistry {
  const modules: WgslModule[] = [
    { name: 'records', requires: [], source: createRecordsWgsl() },
    fromFile('math', []),
    fromFile('sampling', []),
    fromFile('intersect', ['records', 'math']),
    fromFile('bind-scene', ['records']),
    fromFile('bind-wavefront', ['records']),
    fromFile('bvh-traversal', ['intersect', 'bind-scene']),
  ];
  for (const name of optionalModuleNames) {
    if (wgslSources[name] !== undefined) modules.push(fromFile(name, optionalModuleRequires[name] ?? []));
  }
  return createWgslModuleRegistry(modules);
}

/** Modules that later parts of the renderer add, with their requirements. */
const optionalModuleRequires: Record<string, readonly string[]> = {
  fresnel: ['math'],
  microfacet: ['math'],
  'bsdf-gltf': ['records', 'math', 'fresnel', 'microfacet'],
  lights: ['records', 'math', 'bind-scene'],
  camera: ['records', 'math', 'sampling', 'bind-scene', 'bind-wavefront'],
  tonemap: ['math'],
  'kernel-camera': ['bind-scene', 'bind-wavefront', 'camera', 'sampling'],
  'kernel-prepare': ['bind-wavefront'],
  'kernel-extend': ['bind-wavefront', 'bvh-traversal'],
  'kernel-shade': ['bind-wavefront', 'bind-scene', 'sampling', 'camera', 'bsdf-gltf', 'lights'],
  'kernel-shadow': ['bind-wavefront', 'bvh-traversal'],
  'kernel-accumulate': ['bind-scene', 'bind-wavefront'],
  'kernel-resolve': ['records', 'tonemap'],
  'kernel-present': ['records', 'tonemap'],
};
const optionalModuleNames = Object.keys(optionalModuleRequires);

let registry: WgslModuleRegistry | undefined;

export function shaderModuleRegistry(): WgslModuleRegistry {
  registry ??= createShaderModuleRegistry();
  return registry;
}

/** The composed WGSL program for the given entry modules. */
export function composeShader(entries: readonly string[]): string {
  return composeWgsl(shaderModuleRegistry(), entries);
}
