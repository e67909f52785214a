/**
 * Host-shareable struct layouts following WGSL's alignment rules (WGSL spec, "Memory Layout":
 * AlignOf/SizeOf for scalars, vectors and structures). One layout drives both the WGSL struct
 * declaration and the TypeScript packers, so the two cannot drift apart.
 */
export type WgslFieldType = 'f32' | 'u32' | 'i32' | 'vec2f' | 'vec3f' | 'vec4f' | 'vec2u' | 'vec3u' | 'vec4u';

interface TypeInfo {
  scalar: 'f32' | 'u32' | 'i32';
  components: number;
  align: number;
  size: number;
}

const typeInfo: Record<WgslFieldType, TypeInfo> = {
  f32: { scalar: 'f32', components: 1, align: 4, size: 4 },
  u32: { scalar: 'u32', components: 1, align: 4, size: 4 },
  i32: { scalar: 'i32', components: 1, align: 4, size: 4 },
  vec2f: { scalar: 'f32', components: 2, align: 8, size: 8 },
  vec3f: { scalar: 'f32', components: 3, align: 16, size: 12 },
  vec4f: { scalar: 'f32', components: 4, align: 16, size: 16 },
  vec2u: { scalar: 'u32', components: 2, align: 8, size: 8 },
  vec3u: { scalar: 'u32', components: 3, align: 16, size: 12 },
  vec4u: { scalar: 'u32', components: 4, align: 16, size: 16 },
};

export interface StructFieldLayout {
  readonly name: string;
  /** A scalar or vector type, or the name of the nested struct (see `struct`). */
  readonly type: WgslFieldType | string;
  readonly offset: number;
  readonly size: number;
  /** Components of a scalar or vector field; 0 for a nested struct. */
  readonly components: number;
  readonly scalar: 'f32' | 'u32' | 'i32' | null;
  /** The layout of a nested struct field (WGSL structures nest with their own alignment). */
  readonly struct?: StructLayout;
  /** Why the field exists; emitted as a WGSL comment. */
  readonly doc?: string;
}

export interface StructLayout {
  readonly name: string;
  /** Contract version: bump when a field changes meaning or position. */
  readonly version: number;
  readonly fields: readonly StructFieldLayout[];
  readonly size: number;
  readonly align: number;
}

export type StructFieldSpec = readonly [name: string, type: WgslFieldType | StructLayout, doc?: string];

const roundUp = (n: number, k: number): number => Math.ceil(n / k) * k;

export function defineStructLayout(name: string, version: number, specs: readonly StructFieldSpec[]): StructLayout {
  let offset = 0;
  let align = 4;
  const seen = new Set<string>();
  const fields: StructFieldLayout[] = specs.map(([fieldName, type, doc]) => {
    if (seen.has(fieldName)) throw new Error(`struct ${name}: duplicate field ${fieldName}`);
    seen.add(fieldName);
    if (typeof type !== 'string') {
      // A nested structure: AlignOf is its own, SizeOf its (already rounded) size.
      offset = roundUp(offset, type.align);
      align = Math.max(align, type.align);
      const field: StructFieldLayout = Object.freeze({ name: fieldName, type: type.name, offset, size: type.size, components: 0, scalar: null, struct: type, ...(doc ? { doc } : {}) });
      offset += type.size;
      return field;
    }
    const info = typeInfo[type];
    offset = roundUp(offset, info.align);
    align = Math.max(align, info.align);
    const field: StructFieldLayout = Object.freeze({
      name: fieldName,
      type,
      offset,
      size: info.size,
      components: info.components,
      scalar: info.scalar,
      ...(doc ? { doc } : {}),
    });
    offset += info.size;
    return field;
  });
  return Object.freeze({ name, version, fields: Object.freeze(fields), size: roundUp(offset, align), align });
}

/** The WGSL declaration of a layout. */
export function structLayoutToWgsl(layout: StructLayout): string {
  const lines = layout.fields.map((f) => `  ${f.name}: ${f.type},${f.doc ? ` // ${f.doc}` : ''}`);
  return `// ${layout.name} v${layout.version}: ${layout.size} bytes, generated from src/gpu-layout/records.ts\nstruct ${layout.name} {\n${lines.join('\n')}\n}\n`;
}

/** Field values by name; a nested struct field takes the nested struct's values. */
export type StructValues = { [field: string]: number | ArrayLike<number> | StructValues };

/** The scalar and vector fields of a layout, nested structs flattened (dotted names, absolute offsets). */
export function leafFields(layout: StructLayout, prefix = '', base = 0): StructFieldLayout[] {
  return layout.fields.flatMap((f) =>
    f.struct ? leafFields(f.struct, `${prefix}${f.name}.`, base + f.offset) : [{ ...f, name: `${prefix}${f.name}`, offset: base + f.offset }],
  );
}

export function fieldOf(layout: StructLayout, name: string): StructFieldLayout {
  const field = layout.fields.find((f) => f.name === name);
  if (!field) throw new Error(`struct ${layout.name} has no field ${name}`);
  return field;
}

/** Writes `values` (missing fields are zero) into `view` at record `index`. */
export function writeStruct(layout: StructLayout, view: DataView, index: number, values: StructValues): void {
  writeStructAt(layout, view, index * layout.size, values);
}

function writeStructAt(layout: StructLayout, view: DataView, base: number, values: StructValues): void {
  for (const field of layout.fields) {
    const value = values[field.name];
    if (value === undefined) continue;
    if (field.struct) {
      writeStructAt(field.struct, view, base + field.offset, value as StructValues);
      continue;
    }
    if (typeof value === 'object' && !('length' in value)) throw new Error(`struct ${layout.name}: field ${field.name} is not a struct`);
    for (let c = 0; c < field.components; c++) {
      const v = typeof value === 'number' ? (c === 0 ? value : 0) : ((value as ArrayLike<number>)[c] ?? 0);
      const at = base + field.offset + c * 4;
      if (field.scalar === 'f32') view.setFloat32(at, v, true);
      else if (field.scalar === 'u32') view.setUint32(at, v >>> 0, true);
      else view.setInt32(at, v | 0, true);
    }
  }
}

/** Reads record `index`; nested structs come back flattened under dotted names (leafFields). */
export function readStruct(layout: StructLayout, view: DataView, index: number): Record<string, number | number[]> {
  const base = index * layout.size;
  const out: Record<string, number | number[]> = {};
  for (const field of leafFields(layout)) {
    const comps: number[] = [];
    for (let c = 0; c < field.components; c++) {
      const at = base + field.offset + c * 4;
      comps.push(field.scalar === 'f32' ? view.getFloat32(at, true) : field.scalar === 'u32' ? view.getUint32(at, true) : view.getInt32(at, true));
    }
    out[field.name] = field.components === 1 ? comps[0]! : comps;
  }
  return out;
}

/** A zeroed buffer holding `count` records (at least one, since WebGPU bindings cannot be empty). */
export function allocateStructArray(layout: StructLayout, count: number): ArrayBuffer {
  return new ArrayBuffer(Math.max(1, count) * layout.size);
}
