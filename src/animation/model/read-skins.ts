import type { Document, Node } from '@gltf-transform/core';
import { fail } from '../../errors/validate.ts';
import { readFloatAccessor } from '../../io/accessors.ts';
import type { ModelSkin } from './model-types.ts';

/** Skins (glTF 2.0 section 3.7.3): joint node indices, inverse bind matrices, skeleton root. */
export function readSkins(document: Document, indexOf: Map<Node, number>, field: string): ModelSkin[] {
  return document.getRoot().listSkins().map((skin, s) => {
    const skinField = `${field}skins[${s}]`;
    const jointNodes = skin.listJoints();
    if (jointNodes.length === 0) fail('INVALID_MODEL', `${skinField}.joints`, 'skin has no joints');
    const joints = new Int32Array(jointNodes.length);
    jointNodes.forEach((joint, j) => {
      const index = indexOf.get(joint);
      if (index === undefined) fail('INVALID_MODEL', `${skinField}.joints[${j}]`, 'joint node is not part of the document');
      joints[j] = index;
    });
    const inverseBindMatrices = new Float64Array(16 * joints.length);
    const ibm = skin.getInverseBindMatrices();
    if (ibm === null) {
      // "When undefined, each matrix is a 4x4 identity matrix" (glTF 2.0 section 5.28).
      for (let j = 0; j < joints.length; j++) for (let d = 0; d < 4; d++) inverseBindMatrices[16 * j + 5 * d] = 1;
    } else {
      const values = readFloatAccessor(ibm, `${skinField}.inverseBindMatrices`, 'INVALID_MODEL', ['MAT4']);
      if (values.length / 16 < joints.length) {
        fail('INVALID_MODEL', `${skinField}.inverseBindMatrices`, `has ${values.length / 16} matrices for ${joints.length} joints`);
      }
      inverseBindMatrices.set(values.subarray(0, 16 * joints.length));
    }
    const skeletonNode = skin.getSkeleton();
    const skeleton = skeletonNode === null ? -1 : (indexOf.get(skeletonNode) ?? -1);
    return { name: skin.getName(), joints, inverseBindMatrices, skeleton };
  });
}
