import type { Document, Node } from '@gltf-transform/core';
import { fail } from '../../errors/validate.ts';
import type { ModelNode, Quat, Vec3 } from './model-types.ts';

export interface NodeHierarchy {
  readonly nodes: Node[];
  readonly indexOf: Map<Node, number>;
  readonly parents: Int32Array;
  readonly children: number[][];
  /** Parents before children. */
  readonly order: Int32Array;
}

/**
 * Reads the node forest: each node has at most one parent and no cycles (glTF 2.0 section 3.5.1:
 * "node hierarchy MUST be a set of disjoint strict trees").
 */
export function readNodeHierarchy(document: Document, field: string): NodeHierarchy {
  const nodes = document.getRoot().listNodes();
  const indexOf = new Map<Node, number>();
  nodes.forEach((node, i) => indexOf.set(node, i));
  const parents = new Int32Array(nodes.length).fill(-1);
  const children: number[][] = nodes.map(() => []);
  nodes.forEach((node, i) => {
    node.listChildren().forEach((child, c) => {
      const j = indexOf.get(child);
      if (j === undefined) fail('INVALID_MODEL', `${field}nodes[${i}].children[${c}]`, 'child node is not part of the document');
      if (parents[j] !== -1) fail('INVALID_MODEL', `${field}nodes[${i}].children[${c}]`, `node ${j} has two parents (${parents[j]} and ${i})`);
      parents[j] = i;
      children[i].push(j);
    });
  });
  const order = new Int32Array(nodes.length);
  let n = 0;
  const stack: number[] = [];
  for (let i = nodes.length - 1; i >= 0; i--) if (parents[i] === -1) stack.push(i);
  while (stack.length > 0) {
    const i = stack.pop() as number;
    order[n++] = i;
    for (let c = children[i].length - 1; c >= 0; c--) stack.push(children[i][c]);
  }
  if (n !== nodes.length) {
    const visited = new Set(order.subarray(0, n));
    const stuck = nodes.findIndex((_, i) => !visited.has(i));
    fail('INVALID_MODEL', `${field}nodes[${stuck}].children`, 'the node hierarchy contains a cycle');
  }
  return { nodes, indexOf, parents, children, order };
}

function finiteTuple<T extends number[]>(values: ArrayLike<number>, field: string): T {
  const out: number[] = [];
  for (let i = 0; i < values.length; i++) {
    if (!Number.isFinite(values[i])) fail('INVALID_MODEL', `${field}[${i}]`, `expected a finite number, got ${values[i]}`);
    out.push(values[i]);
  }
  return out as T;
}

/** Rest transform and references of one node; weights are filled in by the model reader. */
export function readNodeRest(node: Node, field: string): { translation: Vec3; rotation: Quat; scale: Vec3 } {
  const translation = finiteTuple<Vec3>(node.getTranslation(), `${field}.translation`);
  const rotation = finiteTuple<Quat>(node.getRotation(), `${field}.rotation`);
  const scale = finiteTuple<Vec3>(node.getScale(), `${field}.scale`);
  const length = Math.hypot(rotation[0], rotation[1], rotation[2], rotation[3]);
  if (length < 1e-6) fail('INVALID_MODEL', `${field}.rotation`, 'rotation quaternion has zero length');
  for (let i = 0; i < 4; i++) rotation[i] /= length;
  return { translation, rotation, scale };
}

export type { ModelNode };
