/**
 * One glTF primitive -> triangle-list vertex streams, validated: non-finite vertex data and indices
 * beyond the vertex count are typed errors naming the attribute or indices pointer. Morph targets
 * are applied with the given weights (glTF 2.0 section 3.7.2.2: base + sum of weight * target).
 */
import type { Accessor, Primitive } from '@gltf-transform/core';
import { accessorToFloat32, accessorToUint32, firstNonFinite } from './accessors.ts';
import { failGltf } from './errors.ts';
import { MODE_NAMES, MODE_TRIANGLES, MODE_TRIANGLE_FAN, MODE_TRIANGLE_STRIP, sequentialIndices, toTriangleList } from './topology.ts';
import type { VertexStreams } from './vertex-streams.ts';

const RESTART_VALUES: Readonly<Record<number, number>> = { 5121: 0xff, 5123: 0xffff, 5125: 0xffffffff };

export interface PrimitiveGeometryOptions {
  /** JSON pointer of the primitive (`/meshes/2/primitives/0`). */
  at: string;
  /** Morph target weights (the node's, else the mesh's defaults). */
  weights: readonly number[];
  /** KHR_mesh_primitive_restart is in use: the largest index value restarts strips and fans. */
  primitiveRestart: boolean;
  /** Notes about data left out (the caller prefixes the primitive's pointer). */
  warn?: (message: string) => void;
}

/** Components per element of the attributes the renderer reads (glTF 2.0 section 3.7.2.1). */
const ATTRIBUTE_SIZES: Readonly<Record<string, readonly number[]>> = { POSITION: [3], NORMAL: [3], TANGENT: [4], TEXCOORD_0: [2], TEXCOORD_1: [2], COLOR_0: [3, 4] };

/**
 * The attribute as float32, checked: its element size (a Document passed in has not been through
 * the JSON validation), its count against the primitive's vertex count, and finite components.
 */
function floatAttribute(primitive: Primitive, semantic: string, at: string, vertexCount: number): Float32Array | undefined {
  const accessor = primitive.getAttribute(semantic);
  if (accessor === null) return undefined;
  const sizes = ATTRIBUTE_SIZES[semantic]!;
  if (!sizes.includes(accessor.getElementSize())) failGltf(`${at}/attributes/${semantic}`, `${semantic} must have ${sizes.join(' or ')} components per element, the accessor has ${accessor.getElementSize()}`);
  if (accessor.getCount() !== vertexCount) failGltf(`${at}/attributes/${semantic}`, `${accessor.getCount()} elements, the primitive's POSITION has ${vertexCount}`);
  const values = accessorToFloat32(accessor);
  const bad = firstNonFinite(values);
  if (bad >= 0) failGltf(`${at}/attributes/${semantic}`, `element ${Math.floor(bad / accessor.getElementSize())} has a non-finite component (${values[bad]})`);
  return values;
}

function applyMorphTargets(primitive: Primitive, semantic: string, base: Float32Array | undefined, size: number, options: PrimitiveGeometryOptions): void {
  if (base === undefined) return;
  primitive.listTargets().forEach((target, t) => {
    const weight = options.weights[t] ?? 0;
    const accessor: Accessor | null = target.getAttribute(semantic);
    if (weight === 0 || accessor === null) return;
    if (accessor.getCount() !== base.length / size) failGltf(`${options.at}/targets/${t}/${semantic}`, `${accessor.getCount()} elements, the primitive has ${base.length / size} vertices`);
    const delta = accessorToFloat32(accessor);
    const bad = firstNonFinite(delta);
    if (bad >= 0) failGltf(`${options.at}/targets/${t}/${semantic}`, `element ${Math.floor(bad / accessor.getElementSize())} has a non-finite component`);
    const components = accessor.getElementSize();
    for (let v = 0; v < base.length / size; v++) {
      for (let k = 0; k < Math.min(3, components, size); k++) base[v * size + k] += weight * delta[v * components + k];
    }
  });
}

function renormalize(values: Float32Array | undefined, size: number): void {
  if (values === undefined) return;
  for (let i = 0; i < values.length; i += size) {
    const len = Math.hypot(values[i], values[i + 1], values[i + 2]);
    if (len > 0) for (let k = 0; k < 3; k++) values[i + k] /= len;
  }
}

/**
 * The primitive's triangles, or a reason it has none the renderer can draw (then the caller warns
 * and skips it).
 */
export function primitiveGeometry(primitive: Primitive, options: PrimitiveGeometryOptions): VertexStreams | { skip: string } {
  const { at } = options;
  const mode = primitive.getMode();
  if (mode !== MODE_TRIANGLES && mode !== MODE_TRIANGLE_STRIP && mode !== MODE_TRIANGLE_FAN) {
    return { skip: `${MODE_NAMES[mode] ?? `mode ${mode}`} primitives are not rendered (the path tracer draws surfaces only)` };
  }
  const positionAccessor = primitive.getAttribute('POSITION');
  if (positionAccessor === null) return { skip: 'the primitive has no POSITION attribute' };
  const vertexCount = positionAccessor.getCount();
  const positions = floatAttribute(primitive, 'POSITION', at, vertexCount) as Float32Array;
  const normals = floatAttribute(primitive, 'NORMAL', at, vertexCount);
  const tangents = floatAttribute(primitive, 'TANGENT', at, vertexCount);
  const uvs = floatAttribute(primitive, 'TEXCOORD_0', at, vertexCount);
  const uvs1 = floatAttribute(primitive, 'TEXCOORD_1', at, vertexCount);
  const colors = floatAttribute(primitive, 'COLOR_0', at, vertexCount);

  if (options.weights.some((w) => w !== 0)) {
    applyMorphTargets(primitive, 'POSITION', positions, 3, options);
    applyMorphTargets(primitive, 'NORMAL', normals, 3, options);
    applyMorphTargets(primitive, 'TANGENT', tangents, 4, options);
    renormalize(normals, 3);
    renormalize(tangents, 4);
    const bad = firstNonFinite(positions);
    if (bad >= 0) failGltf(`${at}/targets`, `morphed POSITION element ${Math.floor(bad / 3)} is not finite`);
  }

  const indexAccessor = primitive.getIndices();
  const count = indexAccessor === null ? vertexCount : indexAccessor.getCount();
  if (mode === MODE_TRIANGLES && count % 3 !== 0) options.warn?.(`${count} ${indexAccessor === null ? 'vertices' : 'indices'} are not whole triangles; the last ${count % 3} ignored`);
  let indices: Uint32Array;
  if (indexAccessor === null) {
    indices = toTriangleList(mode, sequentialIndices(vertexCount));
  } else {
    indices = accessorToUint32(indexAccessor);
    const restart = options.primitiveRestart && mode !== MODE_TRIANGLES ? RESTART_VALUES[indexAccessor.getComponentType()] : undefined;
    for (let i = 0; i < indices.length; i++) {
      if (indices[i] >= vertexCount && indices[i] !== restart) failGltf(`${at}/indices`, `index ${i} is ${indices[i]}, the primitive has ${vertexCount} vertices`);
    }
    indices = toTriangleList(mode, indices, restart);
  }
  if (indices.length === 0) return { skip: 'the primitive has no complete triangle' };

  const streams: VertexStreams = { positions, indices };
  if (normals !== undefined) streams.normals = normals;
  if (tangents !== undefined) streams.tangents = tangents;
  if (uvs !== undefined) streams.uvs = uvs;
  if (uvs1 !== undefined) streams.uvs1 = uvs1;
  if (colors !== undefined) streams.colors = colors;
  return streams;
}
