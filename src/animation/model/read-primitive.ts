import type { Material, Primitive } from '@gltf-transform/core';
import { fail } from '../../errors/validate.ts';
import { readFloatAccessor, readIndexAccessor } from '../../io/accessors.ts';
import { readSkinInfluences } from './skin-influences.ts';
import type { ModelMorphTarget, ModelPrimitive } from './model-types.ts';

const TRIANGLES = 4;

function optionalStream(primitive: Primitive, semantic: string, field: string, types: readonly string[], vertexCount: number): Float32Array | null {
  const accessor = primitive.getAttribute(semantic);
  if (accessor === null) return null;
  const attributeField = `${field}.attributes.${semantic}`;
  const values = readFloatAccessor(accessor, attributeField, 'INVALID_MODEL', types);
  if (accessor.getCount() !== vertexCount) {
    fail('INVALID_MODEL', attributeField, `has ${accessor.getCount()} elements but POSITION has ${vertexCount}`);
  }
  return Float32Array.from(values);
}

function readTarget(primitive: Primitive, t: number, field: string, vertexCount: number): ModelMorphTarget {
  const target = primitive.listTargets()[t];
  const targetField = `${field}.targets[${t}]`;
  const stream = (semantic: string): Float32Array | null => {
    const accessor = target.getAttribute(semantic);
    if (accessor === null) return null;
    const values = readFloatAccessor(accessor, `${targetField}.${semantic}`, 'INVALID_MODEL', ['VEC3']);
    if (accessor.getCount() !== vertexCount) {
      fail('INVALID_MODEL', `${targetField}.${semantic}`, `has ${accessor.getCount()} elements but POSITION has ${vertexCount}`);
    }
    return Float32Array.from(values);
  };
  return { positions: stream('POSITION'), normals: stream('NORMAL'), tangents: stream('TANGENT') };
}

/**
 * Reads one triangle primitive's vertex streams, indices, skin influences and morph targets
 * (glTF 2.0 sections 3.7.2 and 3.7.3), checking types, counts and index ranges.
 */
export function readPrimitive(primitive: Primitive, field: string, materialIndexOf: Map<Material, number>): ModelPrimitive {
  if (primitive.getMode() !== TRIANGLES) {
    fail('INVALID_MODEL', `${field}.mode`, `only triangle lists (mode 4) can be animated and drawn, got mode ${primitive.getMode()}`);
  }
  const positionAccessor = primitive.getAttribute('POSITION');
  if (positionAccessor === null) fail('INVALID_MODEL', `${field}.attributes.POSITION`, 'primitive has no POSITION');
  const positions = Float32Array.from(readFloatAccessor(positionAccessor, `${field}.attributes.POSITION`, 'INVALID_MODEL', ['VEC3']));
  const vertexCount = positions.length / 3;
  if (vertexCount === 0) fail('INVALID_MODEL', `${field}.attributes.POSITION`, 'primitive has no vertices');
  const colorAccessor = primitive.getAttribute('COLOR_0');
  const colors = optionalStream(primitive, 'COLOR_0', field, ['VEC3', 'VEC4'], vertexCount);
  let indices: Uint32Array | null = null;
  const indexAccessor = primitive.getIndices();
  if (indexAccessor !== null) {
    indices = readIndexAccessor(indexAccessor, `${field}.indices`, 'INVALID_MODEL', ['SCALAR']);
    if (indices.length % 3 !== 0) fail('INVALID_MODEL', `${field}.indices`, `index count ${indices.length} is not a multiple of 3`);
    for (let i = 0; i < indices.length; i++) {
      if (indices[i] >= vertexCount) fail('INVALID_MODEL', `${field}.indices[${i}]`, `index ${indices[i]} is out of range for ${vertexCount} vertices`);
    }
  } else if (vertexCount % 3 !== 0) {
    fail('INVALID_MODEL', `${field}.attributes.POSITION`, `without indices the vertex count (${vertexCount}) must be a multiple of 3`);
  }
  const influences = readSkinInfluences(primitive, field, vertexCount);
  const targets: ModelMorphTarget[] = [];
  for (let t = 0; t < primitive.listTargets().length; t++) targets.push(readTarget(primitive, t, field, vertexCount));
  const material = primitive.getMaterial();
  return {
    vertexCount,
    positions,
    normals: optionalStream(primitive, 'NORMAL', field, ['VEC3'], vertexCount),
    tangents: optionalStream(primitive, 'TANGENT', field, ['VEC4'], vertexCount),
    uvs: optionalStream(primitive, 'TEXCOORD_0', field, ['VEC2'], vertexCount),
    uvs1: optionalStream(primitive, 'TEXCOORD_1', field, ['VEC2'], vertexCount),
    colors,
    colorComponents: colorAccessor === null ? 0 : colorAccessor.getType() === 'VEC3' ? 3 : 4,
    indices,
    influences: influences.influences,
    joints: influences.joints,
    weights: influences.weights,
    targets,
    material: material === null ? -1 : (materialIndexOf.get(material) ?? -1),
  };
}
