/**
 * The WESL modules generated from the TypeScript layout tables, so structs, constants, bindings,
 * heap loaders and specialisation constants have exactly one definition:
 *
 * - `package::layout::records`: every GPU record struct (gpu-layout/records.ts);
 * - `package::layout::constants`: every shared constant (gpu-layout/constants.ts);
 * - `package::layout::bindings`: the path tracer's binding declarations (gpu-layout/bindings.ts);
 * - `package::layout::display_bindings`: the display resolve's bindings;
 * - `package::layout::bvh_build_bindings`: the GPU BVH builder's bindings (accel/gpu-build/bindings.ts);
 * - `package::layout::oidn_bindings`: the OIDN network's bindings (film/denoise/oidn/bindings.ts);
 * - `package::layout::heaps`: `load_<record>(offset)` readers of records stored in vec4 heaps;
 * - `package::layout::features`: the `override` specialisation constants (shaders/features.ts);
 * - `package::layout::material_layers`: the KHR extension layers of the glTF BSDF (material-layers.ts).
 */
import { bindingDeclaration, pathTracerBindings, type BindingSpec } from '../../src/gpu-layout/bindings.ts';
import { gpuConstants } from '../../src/gpu-layout/constants.ts';
import { heapRecordLayouts, wavefrontRecordLayouts } from '../../src/gpu-layout/records.ts';
import { structLayoutToWgsl, type StructLayout } from '../../src/gpu-layout/struct-layout.ts';
import { oidnBindings } from '../../src/film/denoise/oidn/bindings.ts';
import { displayBindings } from '../../src/shaders/display-bindings.ts';
import { bvhBuildBindings } from '../../src/accel/gpu-build/bindings.ts';
import { shaderFeatures } from '../../src/shaders/features.ts';
import { anyMaterialExtensions } from '../../src/materials/extensions/index.ts';
import { materialLayersModule } from './material-layers.ts';

/** Module path (relative, `/`-separated, `.wesl`) -> source. */
export type WeslSources = Record<string, string>;

const recordNames = Object.keys(wavefrontRecordLayouts);
const constantNames = Object.keys(gpuConstants);

function recordsModule(): string {
  return Object.values(wavefrontRecordLayouts).map(structLayoutToWgsl).join('\n');
}

function constantsModule(): string {
  return Object.entries(gpuConstants)
    .map(([name, value]) => `const ${name}: u32 = ${value >>> 0}u;`)
    .join('\n');
}

/** The struct and constant names a WGSL type expression mentions (for the import list). */
function namesUsedBy(types: readonly string[]): { records: string[]; constants: string[] } {
  const words = new Set(types.flatMap((t) => t.split(/[^A-Za-z0-9_]+/)));
  return { records: recordNames.filter((n) => words.has(n)), constants: constantNames.filter((n) => words.has(n)) };
}

function importLines(used: { records: string[]; constants: string[] }): string {
  const lines: string[] = [];
  if (used.records.length > 0) lines.push(`import package::layout::records::{${used.records.join(', ')}};`);
  if (used.constants.length > 0) lines.push(`import package::layout::constants::{${used.constants.join(', ')}};`);
  return lines.join('\n');
}

function bindingsModule(table: Record<string, BindingSpec>): string {
  const specs = Object.entries(table);
  const imports = importLines(namesUsedBy(specs.map(([, s]) => ('type' in s ? s.type : ''))));
  return `${imports}\n\n${specs.map(([name, spec]) => bindingDeclaration(name, spec)).join('\n')}\n`;
}

function snake(name: string): string {
  return name.replace(/([a-z0-9])([A-Z])/g, '$1_$2').toLowerCase();
}

/**
 * `fn load_<record>(offset: u32) -> Record` reading a record stored at vec4 `offset` of a vec4 heap.
 * Layouts follow WGSL's host-shareable alignment, so no field straddles two vec4s.
 */
function heapLoader(heap: string, layout: StructLayout): string {
  const components = ['x', 'y', 'z', 'w'];
  const args = layout.fields.map((f) => {
    const vec = Math.floor(f.offset / 16);
    const first = (f.offset % 16) / 4;
    const swizzle = components.slice(first, first + f.components).join('');
    const raw = `v${vec}.${swizzle}`;
    if (f.scalar === 'f32') return raw;
    const target = f.components === 1 ? f.scalar : `vec${f.components}<${f.scalar}>`;
    return `bitcast<${target}>(${raw})`;
  });
  const vecCount = layout.size / 16;
  const loads = Array.from({ length: vecCount }, (_, k) => `  let v${k} = ${heap}[offset + ${k}u];`).join('\n');
  const cells = `// Heap cells (vec4s) of one ${layout.name}, the stride of arrays of them.\nconst ${snake(layout.name).toUpperCase()}_CELLS: u32 = ${vecCount}u;\n`;
  return `${cells}// ${layout.name} from the ${heap} heap (${vecCount} vec4s at offset).\nfn load_${snake(layout.name)}(offset: u32) -> ${layout.name} {\n${loads}\n  return ${layout.name}(${args.join(', ')});\n}\n`;
}

function heapsModule(): string {
  const lines: string[] = [];
  const names = new Set<string>();
  for (const [heap, layouts] of Object.entries(heapRecordLayouts)) {
    for (const layout of layouts) {
      if (layout.size % 16 !== 0) throw new Error(`heap record ${layout.name} is ${layout.size} bytes, not a multiple of 16`);
      names.add(layout.name);
      lines.push(heapLoader(heap, layout));
    }
  }
  const heaps = Object.keys(heapRecordLayouts);
  return `import package::layout::records::{${[...names].join(', ')}};\nimport package::layout::bindings::{${heaps.join(', ')}};\n\n${lines.join('\n')}`;
}

function featuresModule(): string {
  const overrides = Object.entries(shaderFeatures).map(([name, f]) => `// ${f.doc}\noverride ${name}: bool = ${f.default};`);
  const extensions = anyMaterialExtensions.map((e) => e.feature.name).join(' || ');
  return `${overrides.join('\n')}\n// Whether any KHR material extension is compiled in (registry order).\nfn any_material_extension() -> bool { return ${extensions}; }\n`;
}

/** The generated layout modules, keyed like files under src/ (see wesl-project.ts). */
export function layoutModules(): WeslSources {
  return {
    'layout/records.wesl': recordsModule(),
    'layout/constants.wesl': constantsModule(),
    'layout/bindings.wesl': bindingsModule(pathTracerBindings),
    'layout/display_bindings.wesl': bindingsModule(displayBindings),
    'layout/bvh_build_bindings.wesl': bindingsModule(bvhBuildBindings),
    'layout/oidn_bindings.wesl': `import package::film::denoise::oidn::precision::Tensor4;\n${bindingsModule(oidnBindings)}`,
    'layout/heaps.wesl': heapsModule(),
    'layout/features.wesl': featuresModule(),
    'layout/material_layers.wesl': materialLayersModule(),
  };
}

/** Vec4 count of a heap record (the unit heap offsets are measured in). */
export function heapVec4s(layout: StructLayout): number {
  return layout.size / 16;
}
