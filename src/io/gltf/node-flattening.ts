/**
 * The node hierarchy of one glTF scene flattened to world matrices (glTF 2.0 section 3.5.3:
 * world = parent world * local, local = T * R * S or the node's matrix). KHR_node_visibility hides
 * a node and its descendants.
 */
import type { Node, Scene } from '@gltf-transform/core';
import type { Visibility } from '@gltf-transform/extensions';
import { IDENTITY, multiply, type Mat4 } from '../../math/mat4.ts';

export interface FlatNode {
  node: Node;
  /** The node's index in the asset (`/nodes/i`). */
  index: number;
  world: Mat4;
}

/**
 * Depth-first, children in order (the order a recursive walk gives), with an explicit stack: a
 * hierarchy thousands of nodes deep is legal glTF and must not exhaust the call stack.
 * `posedWorld`, when given, supplies each node's world matrix (an animation's pose, see posing.ts)
 * in place of the product of the authored matrices.
 */
export function flattenNodes(roots: readonly Node[], nodeIndex: ReadonlyMap<Node, number>, posedWorld?: (index: number) => ArrayLike<number>): FlatNode[] {
  const out: FlatNode[] = [];
  const stack: Array<{ node: Node; parentWorld: readonly number[] }> = [];
  for (let r = roots.length - 1; r >= 0; r--) stack.push({ node: roots[r]!, parentWorld: IDENTITY });
  while (stack.length > 0) {
    const { node, parentWorld } = stack.pop()!;
    const visibility = node.getExtension<Visibility>('KHR_node_visibility');
    if (visibility !== null && !visibility.getVisible()) continue;
    const index = nodeIndex.get(node) ?? -1;
    const world = posedWorld === undefined ? multiply(parentWorld, node.getMatrix()) : Array.from(posedWorld(index));
    out.push({ node, index, world });
    const children = node.listChildren();
    for (let c = children.length - 1; c >= 0; c--) stack.push({ node: children[c]!, parentWorld: world });
  }
  return out;
}

export function sceneRoots(scene: Scene): Node[] {
  return scene.listChildren();
}
