import type { Document, Material, Node } from '@gltf-transform/core';
import { fail } from '../../errors/validate.ts';
import { pointerToDottedField, type PrimitiveFault } from '../../io/gltf/primitive/primitive-fault.ts';
import { readGltfPrimitive, usesPrimitiveRestart } from '../../io/gltf/primitive/read-primitive.ts';
import { checkSkinInfluences } from '../../io/gltf/primitive/skin-influences.ts';
import { readAnimationClips } from '../clips/read-clips.ts';
import { checkClipTargets } from '../clips/bind-clips.ts';
import { readNodeHierarchy, readNodeRest } from './read-node-hierarchy.ts';
import { readSkins } from './read-skins.ts';
import type { AnimatedModel, ModelDrawable, ModelMaterialSummary, ModelMesh, ModelNode, ModelPrimitive } from './model-types.ts';

export interface ReadAnimatedModelOptions {
  /** Prefix of error fields, e.g. `modelAsset` (errors then read `modelAsset.skins[0].joints`). */
  field?: string;
}

/**
 * The primitive reader's faults as this reader's errors: INVALID_MODEL, the JSON pointer as a
 * dotted field after the prefix (`/meshes/0/primitives/1/attributes/WEIGHTS_0/12` ->
 * `modelAsset.meshes[0].primitives[1].attributes.WEIGHTS_0[12]`).
 */
function modelFault(prefix: string): PrimitiveFault {
  return (pointer, message) => fail('INVALID_MODEL', `${prefix}${pointerToDottedField(pointer)}`, message);
}

function readMeshes(document: Document, prefix: string): ModelMesh[] {
  const materialIndexOf = new Map<Material, number>();
  document.getRoot().listMaterials().forEach((material, i) => materialIndexOf.set(material, i));
  const fault = modelFault(prefix);
  const primitiveRestart = usesPrimitiveRestart(document);
  return document.getRoot().listMeshes().map((mesh, m) => {
    const meshField = `${prefix}meshes[${m}]`;
    const primitives = mesh.listPrimitives().map((primitive, p): ModelPrimitive => {
      // Influences are read for every primitive: which skin draws it is known per node (checkSkinnedMesh).
      const read = readGltfPrimitive(primitive, { at: `/meshes/${m}/primitives/${p}`, fault, primitiveRestart, influences: true });
      if ('skip' in read) return fault(read.at, read.skip);
      const material = primitive.getMaterial();
      return { ...read, material: material === null ? -1 : (materialIndexOf.get(material) ?? -1) };
    });
    if (primitives.length === 0) fail('INVALID_MODEL', `${meshField}.primitives`, 'mesh has no primitives');
    const targetCount = primitives[0].targets.length;
    primitives.forEach((primitive, p) => {
      // Section 3.7.2.2: all primitives of a mesh MUST have the same number of targets.
      if (primitive.targets.length !== targetCount) {
        fail('INVALID_MODEL', `${meshField}.primitives[${p}].targets`, `has ${primitive.targets.length} morph targets, primitive 0 has ${targetCount}`);
      }
    });
    const weights = mesh.getWeights();
    if (weights.length !== 0 && weights.length !== targetCount) {
      fail('INVALID_MODEL', `${meshField}.weights`, `has ${weights.length} weights for ${targetCount} morph targets`);
    }
    weights.forEach((w, i) => {
      if (!Number.isFinite(w)) fail('INVALID_MODEL', `${meshField}.weights[${i}]`, `expected a finite number, got ${w}`);
    });
    return { name: mesh.getName(), primitives, weights: weights.length === 0 ? new Array<number>(targetCount).fill(0) : [...weights], targetCount };
  });
}

function summariseMaterials(document: Document): ModelMaterialSummary[] {
  return document.getRoot().listMaterials().map((material) => ({
    name: material.getName(),
    hasBaseColorTexture: material.getBaseColorTexture()?.getImage() != null,
    hasNormalTexture: material.getNormalTexture()?.getImage() != null,
  }));
}

/**
 * Reads the animation-relevant content of a glTF document: node hierarchy with rest TRS, skins,
 * meshes (vertex streams, skin influences, morph targets, read by the one glTF primitive reader, so
 * strips, fans and primitive restart arrive as triangle lists), drawable nodes, a material summary and
 * the document's own animations, validating all of it. Errors are `INVALID_MODEL` or
 * `INVALID_ANIMATION` with a `field` that follows the glTF JSON (`meshes[0].primitives[1].attributes.WEIGHTS_0[12]`).
 */
export function readAnimatedModel(document: Document, options: ReadAnimatedModelOptions = {}): AnimatedModel {
  const fieldRoot = options.field ?? '';
  const prefix = fieldRoot === '' ? '' : `${fieldRoot}.`;
  const hierarchy = readNodeHierarchy(document, prefix);
  const skins = readSkins(document, hierarchy.indexOf, prefix);
  const meshes = readMeshes(document, prefix);
  const skinIndexOf = new Map(document.getRoot().listSkins().map((skin, i) => [skin, i]));
  const meshIndexOf = new Map(document.getRoot().listMeshes().map((mesh, i) => [mesh, i]));
  const drawables: ModelDrawable[] = [];
  const inScene = sceneNodes(document);
  const nodes: ModelNode[] = hierarchy.nodes.map((node, i) => {
    const nodeField = `${prefix}nodes[${i}]`;
    const rest = readNodeRest(node, nodeField);
    const meshRef = node.getMesh();
    const skinRef = node.getSkin();
    const mesh = meshRef === null ? -1 : (meshIndexOf.get(meshRef) ?? -1);
    const skin = skinRef === null ? -1 : (skinIndexOf.get(skinRef) ?? -1);
    let weights: number[] = [];
    if (mesh >= 0) {
      const targetCount = meshes[mesh].targetCount;
      const nodeWeights = node.getWeights();
      if (nodeWeights.length !== 0 && nodeWeights.length !== targetCount) {
        fail('INVALID_MODEL', `${nodeField}.weights`, `has ${nodeWeights.length} weights for ${targetCount} morph targets`);
      }
      weights = nodeWeights.length === 0 ? [...meshes[mesh].weights] : [...nodeWeights];
      if (skin >= 0) checkSkinnedMesh(meshes[mesh], mesh, skins[skin].joints.length, prefix);
      if (inScene === null || inScene.has(node)) drawables.push({ node: i, mesh, skin });
    }
    return { name: node.getName(), parent: hierarchy.parents[i], children: hierarchy.children[i], ...rest, mesh, skin, weights };
  });
  const partial = { nodes, nodeOrder: hierarchy.order, skins, meshes, drawables, materials: summariseMaterials(document), field: fieldRoot };
  const clips = readAnimationClips(document, hierarchy.indexOf, prefix);
  for (const clip of clips) checkClipTargets(partial, clip);
  return { ...partial, clips };
}

/**
 * Nodes of the default scene (or the first scene), which are the ones glTF renders (section
 * 3.5.1); null when the document has no scene, in which case every mesh node is drawn.
 */
function sceneNodes(document: Document): Set<Node> | null {
  const root = document.getRoot();
  const scene = root.getDefaultScene() ?? root.listScenes()[0] ?? null;
  if (scene === null) return null;
  const nodes = new Set<Node>();
  const stack = [...scene.listChildren()];
  while (stack.length > 0) {
    const node = stack.pop() as Node;
    if (nodes.has(node)) continue;
    nodes.add(node);
    stack.push(...node.listChildren());
  }
  return nodes;
}

/** A skinned mesh's primitives must all carry joints, and every joint index must name a skin joint. */
function checkSkinnedMesh(mesh: ModelMesh, meshIndex: number, jointCount: number, prefix: string): void {
  const fault = modelFault(prefix);
  mesh.primitives.forEach((primitive, p) => checkSkinInfluences(primitive, `/meshes/${meshIndex}/primitives/${p}`, jointCount, fault));
}
