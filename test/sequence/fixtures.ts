/**
 * Animated glTF test assets built in code (@gltf-transform), with the hand computations the tests
 * check the loader against.
 *
 * Bending tube: a square tube (half width 0.25, x and z) from y = 0 to y = 2 with vertex rings at
 * RING_HEIGHTS and flat face normals. Two joints: Lower at the Armature's origin, Upper at y = 1
 * above it, all translated by the Armature node's ARMATURE_OFFSET, with inverse bind matrices of
 * that bind pose; the mesh node is translated by (5, 0, 0), which glTF 2.0 section 3.7.3.1 says
 * skinning ignores. Rings at y <= 0.5 follow Lower, y = 1 half each,
 * y >= 1.5 Upper. Animation "Bend" (LINEAR, 1 s) turns Upper about +Z from 0 to 90 degrees;
 * "Sway" (0.5 s) moves Lower along +X by 1. Cameras: "Front" at (0, 1, 6) + offset looking along
 * -Z, "Side" at (6, 1, 0) + offset looking along -X. The material is black and emits white
 * (silhouettes without lighting noise); variants "Red" and "Blue" swap in red and blue emitters.
 */
import { Document, type Accessor, type Buffer as GltfBuffer, type Node } from '@gltf-transform/core';
import { KHRMaterialsVariants } from '@gltf-transform/extensions';

export const RING_HEIGHTS = [0, 0.5, 1, 1.5, 2] as const;
export const HALF_WIDTH = 0.25;
export const ARMATURE_OFFSET = [1, 0, 0] as const;
export const BEND_DEGREES_PER_SECOND = 90;

function accessor(document: Document, buffer: GltfBuffer, type: 'SCALAR' | 'VEC2' | 'VEC3' | 'VEC4' | 'MAT4', values: ArrayLike<number>, array: 'f32' | 'u16' = 'f32'): Accessor {
  return document
    .createAccessor()
    .setType(type)
    .setArray(array === 'u16' ? Uint16Array.from(values) : Float32Array.from(values))
    .setBuffer(buffer);
}

/** Rotation about +Z by `degrees` as a quaternion (x, y, z, w). */
export function rotationZ(degrees: number): [number, number, number, number] {
  const half = (degrees * Math.PI) / 360;
  return [0, 0, Math.sin(half), Math.cos(half)];
}

/** Face normals and (a, b) corner offsets in x/z, counter-clockwise seen from outside. */
const FACES = [
  { normal: [1, 0, 0], a: [HALF_WIDTH, HALF_WIDTH], b: [HALF_WIDTH, -HALF_WIDTH] },
  { normal: [-1, 0, 0], a: [-HALF_WIDTH, -HALF_WIDTH], b: [-HALF_WIDTH, HALF_WIDTH] },
  { normal: [0, 0, 1], a: [-HALF_WIDTH, HALF_WIDTH], b: [HALF_WIDTH, HALF_WIDTH] },
  { normal: [0, 0, -1], a: [HALF_WIDTH, -HALF_WIDTH], b: [-HALF_WIDTH, -HALF_WIDTH] },
] as const;

/** Weight of the Upper joint for a vertex at height y. */
export function upperWeight(y: number): number {
  return y <= 0.5 ? 0 : y >= 1.5 ? 1 : 0.5;
}

export interface TubeVertex {
  position: [number, number, number];
  normal: [number, number, number];
}

/** The tube's bind-pose vertices (mesh space: around the joints, at the Armature's offset), in the order the asset stores them. */
export function tubeVertices(): TubeVertex[] {
  const out: TubeVertex[] = [];
  for (const face of FACES) {
    for (const y of RING_HEIGHTS) {
      out.push({ position: [face.a[0] + ARMATURE_OFFSET[0], y, face.a[1]], normal: [...face.normal] });
      out.push({ position: [face.b[0] + ARMATURE_OFFSET[0], y, face.b[1]], normal: [...face.normal] });
    }
  }
  return out;
}

export interface TubeOptions {
  variants?: boolean;
}

export interface Tube {
  document: Document;
  nodes: { armature: Node; lower: Node; upper: Node; body: Node; front: Node; side: Node };
}

export function createBendingTube(options: TubeOptions = {}): Tube {
  const document = new Document();
  const buffer = document.createBuffer();
  const vertices = tubeVertices();
  const positions = vertices.flatMap((v) => v.position);
  const normals = vertices.flatMap((v) => v.normal);
  const joints = vertices.flatMap(() => [0, 1, 0, 0]);
  const weights = vertices.flatMap((v) => [1 - upperWeight(v.position[1]), upperWeight(v.position[1]), 0, 0]);
  const indices: number[] = [];
  const perFace = 2 * RING_HEIGHTS.length;
  for (let f = 0; f < FACES.length; f++) {
    for (let r = 0; r + 1 < RING_HEIGHTS.length; r++) {
      const a = f * perFace + 2 * r;
      // a, a+1 on this ring; a+2, a+3 on the next (a+1 is to the right of a seen from outside).
      indices.push(a, a + 1, a + 3, a, a + 3, a + 2);
    }
  }
  const material = document.createMaterial('Glow').setBaseColorFactor([0, 0, 0, 1]).setEmissiveFactor([1, 1, 1]);
  const primitive = document
    .createPrimitive()
    .setAttribute('POSITION', accessor(document, buffer, 'VEC3', positions))
    .setAttribute('NORMAL', accessor(document, buffer, 'VEC3', normals))
    .setAttribute('JOINTS_0', accessor(document, buffer, 'VEC4', joints, 'u16'))
    .setAttribute('WEIGHTS_0', accessor(document, buffer, 'VEC4', weights))
    .setIndices(accessor(document, buffer, 'SCALAR', indices, 'u16'))
    .setMaterial(material);
  if (options.variants) {
    const ext = document.createExtension(KHRMaterialsVariants);
    const red = document.createMaterial('Red').setBaseColorFactor([0, 0, 0, 1]).setEmissiveFactor([1, 0, 0]);
    const blue = document.createMaterial('Blue').setBaseColorFactor([0, 0, 0, 1]).setEmissiveFactor([0, 0, 1]);
    const vRed = ext.createVariant('Red');
    const vBlue = ext.createVariant('Blue');
    primitive.setExtension(
      'KHR_materials_variants',
      ext.createMappingList().addMapping(ext.createMapping().setMaterial(red).addVariant(vRed)).addMapping(ext.createMapping().setMaterial(blue).addVariant(vBlue)),
    );
  }
  const mesh = document.createMesh('Tube').addPrimitive(primitive);
  const armature = document.createNode('Armature').setTranslation([...ARMATURE_OFFSET]);
  const lower = document.createNode('Lower');
  const upper = document.createNode('Upper').setTranslation([0, 1, 0]);
  armature.addChild(lower);
  lower.addChild(upper);
  // Inverse bind matrices: the inverse of each joint's bind-time world matrix (pure translations here).
  const ibm = (t: readonly number[]): number[] => [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -t[0]!, -t[1]!, -t[2]!, 1];
  const skin = document
    .createSkin('TubeSkin')
    .addJoint(lower)
    .addJoint(upper)
    .setSkeleton(lower)
    .setInverseBindMatrices(accessor(document, buffer, 'MAT4', [...ibm(ARMATURE_OFFSET), ...ibm([ARMATURE_OFFSET[0], 1, ARMATURE_OFFSET[2]])]));
  const body = document.createNode('Body').setTranslation([5, 0, 0]).setMesh(mesh).setSkin(skin);
  const camera = document.createCamera('FrontCamera').setType('perspective').setYFov((45 * Math.PI) / 180).setZNear(0.1).setAspectRatio(1);
  const front = document.createNode('Front').setCamera(camera).setTranslation([ARMATURE_OFFSET[0], 1, 6]);
  const sideCamera = document.createCamera('SideCamera').setType('perspective').setYFov((45 * Math.PI) / 180).setZNear(0.1).setAspectRatio(1);
  // Looking along -X: a rotation of +90 degrees about +Y takes the camera's -Z to -X.
  const side = document.createNode('Side').setCamera(sideCamera).setTranslation([ARMATURE_OFFSET[0] + 6, 1, 0]).setRotation([0, Math.SQRT1_2, 0, Math.SQRT1_2]);
  document.createScene('Scene').addChild(armature).addChild(body).addChild(front).addChild(side);
  const bend = document.createAnimation('Bend');
  const bendSampler = document
    .createAnimationSampler()
    .setInput(accessor(document, buffer, 'SCALAR', [0, 1]))
    .setOutput(accessor(document, buffer, 'VEC4', [...rotationZ(0), ...rotationZ(BEND_DEGREES_PER_SECOND)]))
    .setInterpolation('LINEAR');
  bend.addSampler(bendSampler).addChannel(document.createAnimationChannel().setTargetNode(upper).setTargetPath('rotation').setSampler(bendSampler));
  const sway = document.createAnimation('Sway');
  const swaySampler = document
    .createAnimationSampler()
    .setInput(accessor(document, buffer, 'SCALAR', [0, 0.5]))
    .setOutput(accessor(document, buffer, 'VEC3', [0, 0, 0, 1, 0, 0]))
    .setInterpolation('LINEAR');
  sway.addSampler(swaySampler).addChannel(document.createAnimationChannel().setTargetNode(lower).setTargetPath('translation').setSampler(swaySampler));
  return { document, nodes: { armature, lower, upper, body, front, side } };
}

/**
 * The skinned vertex by hand: the inverse bind matrices undo the joints' bind-time world matrices,
 * so with the Upper joint turned by `degrees` about +Z at its bind-time pivot c = offset + (0, 1, 0)
 * a vertex of Upper weight w goes to (1 - w) p + w (R (p - c) + c);
 * its normal to R(w degrees) n for w in {0, 1/2, 1} (the normalised inverse transpose of the blend
 * (1 - w) I + w R, a rotation scaled, is the rotation by w times the angle for w = 1/2 too).
 */
export function bentVertex(vertex: TubeVertex, degrees: number): TubeVertex {
  const w = upperWeight(vertex.position[1]);
  const rotate = (v: readonly number[], deg: number): [number, number, number] => {
    const a = (deg * Math.PI) / 180;
    return [Math.cos(a) * v[0]! - Math.sin(a) * v[1]!, Math.sin(a) * v[0]! + Math.cos(a) * v[1]!, v[2]!];
  };
  const [x, y, z] = vertex.position;
  const c = [ARMATURE_OFFSET[0], 1 + ARMATURE_OFFSET[1], ARMATURE_OFFSET[2]];
  const turned = rotate([x - c[0]!, y - c[1]!, z - c[2]!], degrees);
  const upper: [number, number, number] = [turned[0] + c[0]!, turned[1] + c[1]!, turned[2] + c[2]!];
  const position = vertex.position.map((r, k) => (1 - w) * r + w * upper[k]!) as [number, number, number];
  return { position, normal: rotate(vertex.normal, w * degrees) };
}

/**
 * Morphed plane: a 9 x 9 vertex grid over [-1, 1]^2 in x/z at y = 0, normals +Y, two triangles per
 * cell. One morph target: the vertices with |x|, |z| <= PATCH_HALF rise by PATCH_RISE and their
 * normals change by PATCH_NORMAL_DELTA. Animation "Raise" (LINEAR, 1 s) takes its weight from 0 to 1.
 */
export const GRID = 9;
export const PATCH_HALF = 0.5;
export const PATCH_RISE = 0.1;
export const PATCH_NORMAL_DELTA = [0.8, 0, 0] as const;

export function createMorphedPlane(): Document {
  const document = new Document();
  const buffer = document.createBuffer();
  const positions: number[] = [];
  const normals: number[] = [];
  const deltaPositions: number[] = [];
  const deltaNormals: number[] = [];
  for (let j = 0; j < GRID; j++) {
    for (let i = 0; i < GRID; i++) {
      const x = -1 + (2 * i) / (GRID - 1);
      const z = -1 + (2 * j) / (GRID - 1);
      positions.push(x, 0, z);
      normals.push(0, 1, 0);
      const inPatch = Math.abs(x) <= PATCH_HALF + 1e-9 && Math.abs(z) <= PATCH_HALF + 1e-9;
      deltaPositions.push(0, inPatch ? PATCH_RISE : 0, 0);
      deltaNormals.push(...(inPatch ? PATCH_NORMAL_DELTA : [0, 0, 0]));
    }
  }
  const indices: number[] = [];
  for (let j = 0; j + 1 < GRID; j++) {
    for (let i = 0; i + 1 < GRID; i++) {
      const a = j * GRID + i;
      // Counter-clockwise seen from +Y: a, a + GRID, a + 1 (x right, z towards the viewer above).
      indices.push(a, a + GRID, a + 1, a + 1, a + GRID, a + GRID + 1);
    }
  }
  const target = document
    .createPrimitiveTarget('Patch')
    .setAttribute('POSITION', accessor(document, buffer, 'VEC3', deltaPositions))
    .setAttribute('NORMAL', accessor(document, buffer, 'VEC3', deltaNormals));
  const primitive = document
    .createPrimitive()
    .setAttribute('POSITION', accessor(document, buffer, 'VEC3', positions))
    .setAttribute('NORMAL', accessor(document, buffer, 'VEC3', normals))
    .setIndices(accessor(document, buffer, 'SCALAR', indices, 'u16'))
    .setMaterial(document.createMaterial('White').setBaseColorFactor([0.8, 0.8, 0.8, 1]).setMetallicFactor(0).setRoughnessFactor(1))
    .addTarget(target);
  const mesh = document.createMesh('Plane').addPrimitive(primitive).setWeights([0]);
  const node = document.createNode('Plane').setMesh(mesh);
  document.createScene('Scene').addChild(node);
  const raise = document.createAnimation('Raise');
  const sampler = document
    .createAnimationSampler()
    .setInput(accessor(document, buffer, 'SCALAR', [0, 1]))
    .setOutput(accessor(document, buffer, 'SCALAR', [0, 1]))
    .setInterpolation('LINEAR');
  raise.addSampler(sampler).addChannel(document.createAnimationChannel().setTargetNode(node).setTargetPath('weights').setSampler(sampler));
  return document;
}
