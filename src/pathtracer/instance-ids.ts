import { instanceLayout } from '../gpu-layout/records.ts';
import { fieldOf } from '../gpu-layout/struct-layout.ts';
import type { InstanceIds } from '../film/accumulation/readback.ts';
import type { NormalizedScene } from '../scene/normalize-scene.ts';
import { instanceMaterial } from './scene/flatten-primitives.ts';
import type { PreparedScene } from './scene/prepare-scene.ts';

/**
 * Object id (the packed instance record's objectId: the instance's numeric id, else its index) and
 * material index of every instance record, for the id AOVs.
 */
export function instanceIdTables(scene: NormalizedScene, prepared: PreparedScene): InstanceIds {
  const count = scene.instances.length + scene.sceneObjects.length;
  const objectIds = new Int32Array(count);
  const materialIds = new Int32Array(count);
  const view = new DataView(prepared.instances);
  const objectIdOffset = fieldOf(instanceLayout, 'objectId').offset;
  for (let i = 0; i < count; i++) objectIds[i] = view.getUint32(i * instanceLayout.size + objectIdOffset, true);
  scene.instances.forEach((inst, i) => (materialIds[i] = instanceMaterial(scene, inst)));
  // Analytic scene objects own their materials, numbered after the scene's.
  scene.sceneObjects.forEach((_, k) => (materialIds[scene.instances.length + k] = scene.materials.length + k));
  return { objectIds, materialIds };
}
