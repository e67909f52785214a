import { GpuRendererError } from '../../errors/gpu-renderer-error.ts';
import { INDEX_NONE, LIGHT_FLAG_DOUBLE_SIDED, LIGHT_FLAG_TEXTURED, LIGHT_KIND_TRIANGLE } from '../../gpu-layout/constants.ts';
import { lightRecordLayout } from '../../gpu-layout/records.ts';
import { allocateStructArray, writeStruct } from '../../gpu-layout/struct-layout.ts';
import { buildAliasTable } from '../../lighting/alias-table.ts';
import { luminance } from '../../lighting/emissive-lights.ts';
import { maxEmittedPower } from '../../scene/limits.ts';
import { isEmissive } from '../../scene/material.ts';
import type { NormalizedScene } from '../../scene/normalize-scene.ts';
import { applyTextureTransform } from '../../scene/texture-transform.ts';
import { instanceMaterial, transformPoint } from './flatten-primitives.ts';
import type { TextureInfoOffsets } from './pack-materials.ts';

/** The emitters of a scene: one LightRecord per triangle of every emitting instance. */
export interface LightTable {
  records: ArrayBuffer;
  count: number;
  /** Per instance: light index of its triangle 0, or INDEX_NONE when it does not emit. */
  lightBase: Uint32Array;
  /** Estimated emitted power (sum of area x luminance x sides x pi). */
  totalPower: number;
}

/**
 * Light records of every triangle of every emitting instance (world space, winding fixed so that
 * cross(e1, e2) is the front normal), selected in proportion to power (area x luminance of the
 * emission factor, twice for two-sided emitters) through a Walker/Vose alias table. A zero-area
 * triangle gets probability 0 and is never chosen. Power that overflows is a typed error naming
 * the material.
 */
export function buildLightTable(scene: NormalizedScene, infoOffset: TextureInfoOffsets): LightTable {
  const lightBase = new Uint32Array(scene.instances.length + scene.sceneObjects.length).fill(INDEX_NONE);
  let count = 0;
  scene.instances.forEach((inst, i) => {
    if (!isEmissive(scene.materials[instanceMaterial(scene, inst)]!)) return;
    lightBase[i] = count;
    count += scene.meshes[inst.mesh]!.triangleCount;
  });
  const records = allocateStructArray(lightRecordLayout, count);
  if (count === 0) return { records, count, lightBase, totalPower: 0 };
  const view = new DataView(records);
  const power = new Float64Array(count);
  const w = new Float64Array(9);
  let k = 0;
  scene.instances.forEach((inst, i) => {
    if (lightBase[i] === INDEX_NONE) return;
    const materialIndex = instanceMaterial(scene, inst);
    const material = scene.materials[materialIndex]!;
    const mesh = scene.meshes[inst.mesh]!;
    const mirrored = inst.determinant < 0;
    const texture = material.emissiveTexture;
    const uvs = texture ? (texture.texCoord === 1 ? mesh.uvs1 : mesh.uvs) : null;
    const sides = material.doubleSided ? 2 : 1;
    for (let t = 0; t < mesh.triangleCount; t++, k++) {
      // A mirroring transform reverses the winding: swap v1 and v2 so cross(e1, e2) stays the front.
      const corner = [0, mirrored ? 2 : 1, mirrored ? 1 : 2];
      corner.forEach((c, j) => {
        const v = mesh.indices[3 * t + c]!;
        transformPoint(inst, mesh.positions[3 * v]!, mesh.positions[3 * v + 1]!, mesh.positions[3 * v + 2]!, w, 3 * j);
      });
      const e1 = [w[3]! - w[0]!, w[4]! - w[1]!, w[5]! - w[2]!];
      const e2 = [w[6]! - w[0]!, w[7]! - w[1]!, w[8]! - w[2]!];
      const area = 0.5 * Math.hypot(e1[1]! * e2[2]! - e1[2]! * e2[1]!, e1[2]! * e2[0]! - e1[0]! * e2[2]!, e1[0]! * e2[1]! - e1[1]! * e2[0]!);
      power[k] = area * luminance(material.emission) * sides * Math.PI;
      if (!(power[k]! <= maxEmittedPower)) {
        throw new GpuRendererError('SCENE_TOO_LARGE', `an emitting triangle's power ${power[k]} (area ${area}, emission ${material.emission.join(', ')}) exceeds the supported ${maxEmittedPower}`, {
          field: scene.materialFields[materialIndex]!,
        });
      }
      const uv = (j: number): [number, number] => {
        if (!uvs || !texture) return [0, 0];
        const v = mesh.indices[3 * t + corner[j]!]!;
        return applyTextureTransform(texture.transform, uvs[2 * v]!, uvs[2 * v + 1]!);
      };
      writeStruct(lightRecordLayout, view, k, {
        v0: [w[0]!, w[1]!, w[2]!],
        kind: LIGHT_KIND_TRIANGLE,
        e1,
        flags: (material.doubleSided ? LIGHT_FLAG_DOUBLE_SIDED : 0) | (texture && uvs ? LIGHT_FLAG_TEXTURED : 0),
        e2,
        instance: i,
        emission: material.emission,
        primitive: t,
        area,
        uv0: uv(0),
        uv1: uv(1),
        uv2: uv(2),
        texture: texture && uvs ? infoOffset(texture.texture, true) : INDEX_NONE,
      });
    }
  });
  const totalPower = power.reduce((a, b) => a + b, 0);
  if (!(totalPower <= maxEmittedPower)) throw new GpuRendererError('SCENE_TOO_LARGE', `the scene's emitted power ${totalPower} exceeds the supported ${maxEmittedPower}`, { field: 'meshes' });
  if (!(totalPower > 0)) return { records: allocateStructArray(lightRecordLayout, 1), count: 0, lightBase: lightBase.fill(INDEX_NONE), totalPower: 0 };
  const table = buildAliasTable(power);
  for (let l = 0; l < count; l++) {
    writeStruct(lightRecordLayout, view, l, { pmf: table.pmf[l]!, aliasThreshold: table.threshold[l]!, aliasIndex: table.alias[l]! });
  }
  return { records, count, lightBase, totalPower };
}
