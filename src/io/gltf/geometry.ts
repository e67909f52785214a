/**
 * One glTF primitive -> triangle-list vertex streams, validated: non-finite vertex data and indices
 * beyond the vertex count are typed errors naming the attribute or indices pointer. Morph targets
 * are applied with the given weights (glTF 2.0 section 3.7.2.2: base + sum of weight * target), then
 * the node's skin when it has one (section 3.7.3), by src/animation's reference code.
 */
import type { Accessor, Primitive } from '@gltf-transform/core';
import type { ModelMorphTarget } from '../../animation/model/model-types.ts';
import { checkJointRange, readSkinInfluences, type SkinInfluences } from '../../animation/model/skin-influences.ts';
import { applyMorphTargets } from '../../animation/skinning/morph-targets.ts';
import { skinVertices } from '../../animation/skinning/skin-vertices.ts';
import { accessorToFloat32, accessorToUint32, firstNonFinite } from '../accessors.ts';
import { failGltf } from './errors.ts';
import { withGltfPointers } from './posing.ts';
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
  /**
   * The skin of the node drawing the primitive: its joint matrices (16 per joint, column-major,
   * world x inverse bind) and joint count. The vertices come out skinned into world space
   * (section 3.7.3.1: the skinned node's own transform does not apply).
   */
  skin?: { jointMatrices: Float64Array; jointCount: number };
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

/** Morph target deltas of the targets with a non-zero weight (the others are never read). */
function morphTargets(primitive: Primitive, vertexCount: number, options: PrimitiveGeometryOptions): ModelMorphTarget[] {
  return primitive.listTargets().map((target, t) => {
    const read = (semantic: string): Float32Array | null => {
      const accessor: Accessor | null = target.getAttribute(semantic);
      if ((options.weights[t] ?? 0) === 0 || accessor === null) return null;
      const at = `${options.at}/targets/${t}/${semantic}`;
      if (accessor.getElementSize() !== 3) failGltf(at, `morph target ${semantic} deltas must have 3 components per element, the accessor has ${accessor.getElementSize()}`);
      if (accessor.getCount() !== vertexCount) failGltf(at, `${accessor.getCount()} elements, the primitive has ${vertexCount} vertices`);
      const delta = accessorToFloat32(accessor);
      const bad = firstNonFinite(delta);
      if (bad >= 0) failGltf(at, `element ${Math.floor(bad / 3)} has a non-finite component`);
      return delta;
    };
    return { positions: read('POSITION'), normals: read('NORMAL'), tangents: read('TANGENT') };
  });
}

/** The primitive's joint influences for skinning, checked against the skin's joint count. */
function jointInfluences(primitive: Primitive, at: string, vertexCount: number, jointCount: number): SkinInfluences {
  // src/animation names fields with dots (`meshes.0.primitives.1.attributes.JOINTS_0[5]`), made pointers again on error.
  const dotted = at.slice(1).replaceAll('/', '.');
  return withGltfPointers(() => {
    const influences = readSkinInfluences(primitive, dotted, vertexCount);
    if (influences.influences === 0) failGltf(`${at}/attributes/JOINTS_0`, 'the mesh is drawn by a node with a skin; a skinned mesh needs JOINTS_0 and WEIGHTS_0');
    checkJointRange(influences, dotted, jointCount);
    return influences;
  });
}

function normalized(values: Float64Array | null, size: number): Float32Array | undefined {
  if (values === null) return undefined;
  const out = Float32Array.from(values);
  for (let i = 0; i < out.length; i += size) {
    const len = Math.hypot(out[i], out[i + 1], out[i + 2]);
    if (len > 0) for (let k = 0; k < 3; k++) out[i + k] /= len;
  }
  return out;
}

/**
 * Morph targets, then (with a skin) linear blend skinning, by src/animation's reference code (the
 * arithmetic the raster renderer's skinning shader mirrors). Normals and tangents come out unit length.
 */
function deform(primitive: Primitive, base: { positions: Float32Array; normals?: Float32Array; tangents?: Float32Array }, options: PrimitiveGeometryOptions): { positions: Float32Array; normals?: Float32Array; tangents?: Float32Array } {
  const vertexCount = base.positions.length / 3;
  const source = { vertexCount, positions: base.positions, normals: base.normals ?? null, tangents: base.tangents ?? null, targets: morphTargets(primitive, vertexCount, options) };
  const morphed = applyMorphTargets(source, options.weights);
  const streams = options.skin === undefined ? morphed : skinVertices({ vertexCount, ...jointInfluences(primitive, options.at, vertexCount, options.skin.jointCount) }, morphed, options.skin.jointMatrices);
  const positions = Float32Array.from(streams.positions);
  const bad = firstNonFinite(positions);
  if (bad >= 0) failGltf(options.skin === undefined ? `${options.at}/targets` : `${options.at}/attributes/JOINTS_0`, `${options.skin === undefined ? 'morphed' : 'skinned'} POSITION element ${Math.floor(bad / 3)} is not finite`);
  const out: { positions: Float32Array; normals?: Float32Array; tangents?: Float32Array } = { positions };
  const normals = normalized(streams.normals, 3);
  const tangents = normalized(streams.tangents, 4);
  if (normals !== undefined) out.normals = normals;
  if (tangents !== undefined) out.tangents = tangents;
  return out;
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
  let positions = floatAttribute(primitive, 'POSITION', at, vertexCount) as Float32Array;
  let normals = floatAttribute(primitive, 'NORMAL', at, vertexCount);
  let tangents = floatAttribute(primitive, 'TANGENT', at, vertexCount);
  const uvs = floatAttribute(primitive, 'TEXCOORD_0', at, vertexCount);
  const uvs1 = floatAttribute(primitive, 'TEXCOORD_1', at, vertexCount);
  const colors = floatAttribute(primitive, 'COLOR_0', at, vertexCount);
  if (options.weights.some((w) => w !== 0) || options.skin !== undefined) ({ positions, normals, tangents } = deform(primitive, { positions, ...(normals ? { normals } : {}), ...(tangents ? { tangents } : {}) }, options));

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
