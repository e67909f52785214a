/**
 * The node hierarchy of one glTF scene flattened to world matrices (glTF 2.0 section 3.5.3:
 * world = parent world * local, local = T * R * S or the node's matrix). KHR_node_visibility hides
 * a node and its descendants.
 */
import type { Node, Scene } from '@gltf-transform/core';
import type { Visibility } from '@gltf-transform/extensions';
import { IDENTITY, multiply, type Mat4 } from './matrix.ts';

export interface FlatNode {
  node: Node;
  /** The node's index in the asset (`/nodes/i`). */
  index: number;
  world: Mat4;
}

/**
 * `posedWorld`, when given, supplies each node's world matrix (an animation's pose, see posing.ts)
 * in place of the product of the authored matrices.
 */
export function flattenNodes(roots: readonly Node[], nodeIndex: ReadonlyMap<Node, number>, posedWorld?: (index: number) => ArrayLike<number>): FlatNode[] {
  const out: FlatNode[] = [];
  const visit = (node: Node, parentWorld: readonly number[]): void => {
    const visibility = node.getExtension<Visibility>('KHR_node_visibility');
    if (visibility !== null && !visibility.getVisible()) return;
    const index = nodeIndex.get(node) ?? -1;
    const world = posedWorld === undefined ? multiply(parentWorld, node.getMatrix()) : Array.from(posedWorld(index));
    out.push({ node, index, world });
    for (const child of node.listChildren()) visit(child, world);
  };
  for (const root of roots) visit(root, IDENTITY);
  return out;
}

export function sceneRoots(scene: Scene): Node[] {
  return scene.listChildren();
}
