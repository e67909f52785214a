/**
 * The alpha-test record of one triangle (alphaPrimitiveLayout): its three base-colour uvs with
 * KHR_texture_transform applied, vertex-colour alphas and the material's alpha terms, what
 * any-hit and closest-hit traversal read to alpha test it (alpha-test.wesl).
 */
import { ALPHA_MODE_BLEND, ALPHA_MODE_MASK, INDEX_NONE } from '../../gpu-layout/constants.ts';
import { alphaPrimitiveLayout } from '../../gpu-layout/records.ts';
import { writeStruct } from '../../gpu-layout/struct-layout.ts';
import type { NormalizedMaterial } from '../../scene/material.ts';
import type { NormalizedMesh } from '../../scene/mesh.ts';
import { applyTextureTransform } from '../../scene/texture-transform.ts';
import type { TextureInfoOffsets } from './pack-materials.ts';

export function writeAlphaRecord(view: DataView, index: number, mesh: NormalizedMesh, material: NormalizedMaterial, triangle: number, infoOffset: TextureInfoOffsets): void {
  const texture = material.baseColorTexture;
  const uvs = texture ? (texture.texCoord === 1 ? mesh.uvs1 : mesh.uvs) : null;
  const vertex = (c: number): number => mesh.indices[3 * triangle + c]!;
  const uv = (c: number): [number, number] => (uvs && texture ? applyTextureTransform(texture.transform, uvs[2 * vertex(c)]!, uvs[2 * vertex(c) + 1]!) : [0, 0]);
  const vertexAlpha = (c: number): number => (mesh.colors ? mesh.colors[4 * vertex(c) + 3]! : 1);
  writeStruct(alphaPrimitiveLayout, view, index, {
    uv0: uv(0),
    uv1: uv(1),
    uv2: uv(2),
    alphaCutoff: material.alphaCutoff,
    alphaMode: material.alphaMode === 'MASK' ? ALPHA_MODE_MASK : ALPHA_MODE_BLEND,
    vertexAlpha: [vertexAlpha(0), vertexAlpha(1), vertexAlpha(2)],
    alphaFactor: material.baseColor[3],
    texture: texture && uvs ? infoOffset(texture.texture, true) : INDEX_NONE,
  });
}
