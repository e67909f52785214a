/**
 * The one reader of a glTF mesh primitive (glTF 2.0 sections 3.7.2 and 3.7.3), shared by the path
 * tracer's scene loader and the animated-model reader: float vertex streams, a triangle list
 * (strips, fans and KHR_mesh_primitive_restart converted, ./topology.ts), joint influences and
 * morph target deltas, each checked once: element sizes (a Document handed in has not been
 * through the JSON validation), counts against POSITION, finite values and index ranges. Faults
 * go to the caller's reporter with a JSON pointer (./primitive-fault.ts); what is read is left
 * unposed (morphing and skinning are the caller's).
 */
import type { Accessor, Document, Primitive } from '@gltf-transform/core';
import { accessorToFloat32, accessorToUint32, firstNonFinite } from '../../accessors.ts';
import type { PrimitiveFault } from './primitive-fault.ts';
import { readSkinInfluences, type SkinInfluences } from './skin-influences.ts';
import { MODE_NAMES, MODE_TRIANGLES, MODE_TRIANGLE_FAN, MODE_TRIANGLE_STRIP, sequentialIndices, toTriangleList } from './topology.ts';

/** Morph target deltas (section 3.7.2.2); tangent deltas are xyz only. Null: absent, or not read. */
export interface GltfMorphTarget {
  readonly positions: Float32Array | null;
  readonly normals: Float32Array | null;
  readonly tangents: Float32Array | null;
}

/** A primitive as read: its vertex streams, triangles, influences and morph targets. */
export interface GltfPrimitive extends SkinInfluences {
  readonly vertexCount: number;
  /** xyz per vertex. */
  readonly positions: Float32Array;
  readonly normals: Float32Array | null;
  /** xyzw per vertex (w = bitangent sign). */
  readonly tangents: Float32Array | null;
  readonly uvs: Float32Array | null;
  readonly uvs1: Float32Array | null;
  /** COLOR_0 as floats, `colorComponents` (3 or 4) per vertex. */
  readonly colors: Float32Array | null;
  readonly colorComponents: 0 | 3 | 4;
  /** Triangle list, counter-clockwise (a strip's or fan's triangles, or sequential for a primitive without indices). */
  readonly indices: Uint32Array;
  /** One per morph target of the primitive, in order. */
  readonly targets: readonly GltfMorphTarget[];
}

/** Why a primitive has nothing to draw, and the pointer of the cause; the caller warns and skips it, or refuses it. */
export interface SkippedPrimitive {
  readonly skip: string;
  readonly at: string;
}

export interface ReadPrimitiveOptions {
  /** JSON pointer of the primitive (`/meshes/2/primitives/0`); faults name pointers below it. */
  readonly at: string;
  readonly fault: PrimitiveFault;
  /** KHR_mesh_primitive_restart is in use: the largest index value restarts strips and fans. */
  readonly primitiveRestart: boolean;
  /** Read JOINTS_n / WEIGHTS_n. A caller that never skins the primitive leaves them unread (and unchecked). */
  readonly influences: boolean;
  /** Which morph targets to read (default all); the others come back with null deltas, unread. */
  readonly readTarget?: (index: number) => boolean;
  /**
   * Told about data left out: the incomplete last triangle of a TRIANGLES primitive. Without it
   * such data is a fault instead, so a caller with no warning channel loses nothing silently.
   */
  readonly warn?: (message: string) => void;
}

const RESTART_VALUES: Readonly<Record<number, number>> = { 5121: 0xff, 5123: 0xffff, 5125: 0xffffffff };

/** Components per element of the attributes read (section 3.7.2.1). */
const ATTRIBUTE_SIZES: Readonly<Record<string, readonly number[]>> = { POSITION: [3], NORMAL: [3], TANGENT: [4], TEXCOORD_0: [2], TEXCOORD_1: [2], COLOR_0: [3, 4] };

/** Whether the document uses KHR_mesh_primitive_restart (then strips and fans may restart). */
export function usesPrimitiveRestart(document: Document): boolean {
  return document.getRoot().listExtensionsUsed().some((extension) => extension.extensionName === 'KHR_mesh_primitive_restart');
}

/** A float vertex stream (an attribute or morph target deltas), checked: element size, count, finite components. */
function floatStream(accessor: Accessor, at: string, sizes: readonly number[], vertexCount: number, fault: PrimitiveFault, delta = false): Float32Array {
  const size = accessor.getElementSize();
  if (!sizes.includes(size)) fault(at, `${delta ? 'morph target deltas' : 'the attribute'} must have ${sizes.join(' or ')} components per element, the accessor has ${size}`);
  if (accessor.getCount() !== vertexCount) fault(at, `${accessor.getCount()} elements, ${delta ? `the primitive has ${vertexCount} vertices` : `the primitive's POSITION has ${vertexCount}`}`);
  const values = accessorToFloat32(accessor);
  const bad = firstNonFinite(values);
  if (bad >= 0) fault(at, `element ${Math.floor(bad / size)} has a non-finite component (${values[bad]})`);
  return values;
}

function attribute(primitive: Primitive, semantic: string, options: ReadPrimitiveOptions, vertexCount: number): Float32Array | null {
  const accessor = primitive.getAttribute(semantic);
  if (accessor === null) return null;
  return floatStream(accessor, `${options.at}/attributes/${semantic}`, ATTRIBUTE_SIZES[semantic]!, vertexCount, options.fault);
}

function morphTargets(primitive: Primitive, options: ReadPrimitiveOptions, vertexCount: number): GltfMorphTarget[] {
  return primitive.listTargets().map((target, t) => {
    const read = options.readTarget?.(t) ?? true;
    const delta = (semantic: string): Float32Array | null => {
      const accessor = target.getAttribute(semantic);
      if (!read || accessor === null) return null;
      return floatStream(accessor, `${options.at}/targets/${t}/${semantic}`, [3], vertexCount, options.fault, true);
    };
    return { positions: delta('POSITION'), normals: delta('NORMAL'), tangents: delta('TANGENT') };
  });
}

/** The primitive's indices as a triangle list, checked against the vertex count. */
function triangleList(primitive: Primitive, mode: number, options: ReadPrimitiveOptions, vertexCount: number): Uint32Array {
  const { at, fault } = options;
  const accessor = primitive.getIndices();
  const count = accessor === null ? vertexCount : accessor.getCount();
  if (mode === MODE_TRIANGLES && count % 3 !== 0) {
    const what = `${count} ${accessor === null ? 'vertices' : 'indices'} are not whole triangles`;
    if (options.warn !== undefined) options.warn(`${what}; the last ${count % 3} ignored`);
    else fault(accessor === null ? `${at}/attributes/POSITION` : `${at}/indices`, `${what} (a triangle list needs a multiple of 3)`);
  }
  if (accessor === null) return toTriangleList(mode, sequentialIndices(vertexCount));
  const restart = RESTART_VALUES[accessor.getComponentType()];
  if (restart === undefined || accessor.getElementSize() !== 1 || accessor.getNormalized()) {
    fault(`${at}/indices`, `indices must be unsigned byte/short/int scalars, the accessor is ${accessor.getType()} of ${accessor.getComponentType()}${accessor.getNormalized() ? ', normalized' : ''}`);
  }
  const indices = accessorToUint32(accessor);
  const restartValue = options.primitiveRestart && mode !== MODE_TRIANGLES ? restart : undefined;
  for (let i = 0; i < indices.length; i++) {
    if (indices[i] >= vertexCount && indices[i] !== restartValue) fault(`${at}/indices`, `index ${i} is ${indices[i]}, the primitive has ${vertexCount} vertices`);
  }
  return toTriangleList(mode, indices, restartValue);
}

/**
 * Reads one primitive, or says why it has nothing to draw: a mode without surfaces (points,
 * lines), no POSITION, no vertices or no complete triangle.
 */
export function readGltfPrimitive(primitive: Primitive, options: ReadPrimitiveOptions): GltfPrimitive | SkippedPrimitive {
  const { at } = options;
  const mode = primitive.getMode();
  if (mode !== MODE_TRIANGLES && mode !== MODE_TRIANGLE_STRIP && mode !== MODE_TRIANGLE_FAN) {
    return { skip: `${MODE_NAMES[mode] ?? `mode ${mode}`} primitives have no surface to draw (TRIANGLES, TRIANGLE_STRIP and TRIANGLE_FAN do)`, at: `${at}/mode` };
  }
  const positionAccessor = primitive.getAttribute('POSITION');
  if (positionAccessor === null) return { skip: 'the primitive has no POSITION attribute', at: `${at}/attributes/POSITION` };
  const vertexCount = positionAccessor.getCount();
  if (vertexCount === 0) return { skip: 'the primitive has no vertices', at: `${at}/attributes/POSITION` };
  const positions = attribute(primitive, 'POSITION', options, vertexCount)!;
  const colors = attribute(primitive, 'COLOR_0', options, vertexCount);
  const indices = triangleList(primitive, mode, options, vertexCount);
  if (indices.length === 0) return { skip: 'the primitive has no complete triangle', at: primitive.getIndices() === null ? `${at}/attributes/POSITION` : `${at}/indices` };
  const influences: SkinInfluences = options.influences ? readSkinInfluences(primitive, at, vertexCount, options.fault) : { influences: 0, joints: null, weights: null };
  return {
    vertexCount,
    positions,
    normals: attribute(primitive, 'NORMAL', options, vertexCount),
    tangents: attribute(primitive, 'TANGENT', options, vertexCount),
    uvs: attribute(primitive, 'TEXCOORD_0', options, vertexCount),
    uvs1: attribute(primitive, 'TEXCOORD_1', options, vertexCount),
    colors,
    colorComponents: colors === null ? 0 : (primitive.getAttribute('COLOR_0')!.getElementSize() as 3 | 4),
    indices,
    ...influences,
    targets: morphTargets(primitive, options, vertexCount),
  };
}
