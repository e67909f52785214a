import type { Document, Material, Node } from '@gltf-transform/core';
import { fail } from '../../errors/validate.ts';
import { readAnimationClips } from '../clips/read-clips.ts';
import { checkClipTargets } from '../clips/bind-clips.ts';
import { readNodeHierarchy, readNodeRest } from './read-node-hierarchy.ts';
import { readPrimitive } from './read-primitive.ts';
import { readSkins } from './read-skins.ts';
import { checkJointRange } from './skin-influences.ts';
import type { AnimatedModel, ModelDrawable, ModelMaterialSummary, ModelMesh, ModelNode } from './model-types.ts';

export interface ReadAnimatedModelOptions {
  /** Prefix of error fields, e.g. `modelAsset` (errors then read `modelAsset.skins[0].joints`). */
  field?: string;
}

function readMeshes(document: Document, field: string): ModelMesh[] {
  const materialIndexOf = new Map<Material, number>();
  document.getRoot().listMaterials().forEach((material, i) => materialIndexOf.set(material, i));
  return document.getRoot().listMeshes().map((mesh, m) => {
    const meshField = `${field}meshes[${m}]`;
    const primitives = mesh.listPrimitives().map((primitive, p) => readPrimitive(primitive, `${meshField}.primitives[${p}]`, materialIndexOf));
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
 * meshes (vertex streams, skin influences, morph targets), drawable nodes, a material summary and
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
  mesh.primitives.forEach((primitive, p) => {
    const field = `${prefix}meshes[${meshIndex}].primitives[${p}]`;
    if (primitive.joints === null) fail('INVALID_MODEL', `${field}.attributes.JOINTS_0`, 'a skinned mesh needs JOINTS_0 and WEIGHTS_0');
    checkJointRange(primitive, field, jointCount);
  });
}
