/**
 * glTF materials -> WavefrontMaterialInput: the core metallic-roughness factors and textures
 * (glTF 2.0 section 3.9) and the KHR_materials_* extensions' factors and textures under their glTF
 * names. Extension factors are written only for materials that carry the extension, so a missing
 * one keeps the renderer's (the extension's) default.
 */
import type { Material, Texture, TextureInfo } from '@gltf-transform/core';
import type {
  Anisotropy,
  Clearcoat,
  DiffuseTransmission,
  Dispersion,
  EmissiveStrength,
  IOR,
  Iridescence,
  PBRSpecularGlossiness,
  Sheen,
  Specular,
  Transmission,
  Unlit,
  Volume,
} from '@gltf-transform/extensions';
import type { WavefrontImageInput, WavefrontMaterialInput, WavefrontTextureRefInput } from '../../scene/types.ts';
import type { TextureTable } from './textures.ts';

type Slot = keyof WavefrontMaterialInput;

export async function mapMaterial(material: Material, at: string, table: TextureTable): Promise<WavefrontMaterialInput> {
  const out: WavefrontMaterialInput = {
    baseColorFactor: [...material.getBaseColorFactor()],
    metallicFactor: material.getMetallicFactor(),
    roughnessFactor: material.getRoughnessFactor(),
    emissiveFactor: [...material.getEmissiveFactor()],
    alphaMode: material.getAlphaMode(),
    doubleSided: material.getDoubleSided(),
  };
  if (material.getName() !== '') out.name = material.getName();
  if (material.getAlphaMode() === 'MASK') out.alphaCutoff = material.getAlphaCutoff();

  const slot = async (name: Slot, texture: Texture | null, info: TextureInfo | null, slotAt: string, extra?: Partial<WavefrontTextureRefInput>): Promise<void> => {
    const ref = await table.reference(texture, info, slotAt);
    if (ref !== undefined) (out as Record<string, unknown>)[name] = extra === undefined ? ref : { ...ref, ...extra };
  };
  const pbr = `${at}/pbrMetallicRoughness`;
  await slot('baseColorTexture', material.getBaseColorTexture(), material.getBaseColorTextureInfo(), `${pbr}/baseColorTexture`);
  await slot('metallicRoughnessTexture', material.getMetallicRoughnessTexture(), material.getMetallicRoughnessTextureInfo(), `${pbr}/metallicRoughnessTexture`);
  await slot('normalTexture', material.getNormalTexture(), material.getNormalTextureInfo(), `${at}/normalTexture`, { scale: material.getNormalScale() });
  await slot('occlusionTexture', material.getOcclusionTexture(), material.getOcclusionTextureInfo(), `${at}/occlusionTexture`, { strength: material.getOcclusionStrength() });
  await slot('emissiveTexture', material.getEmissiveTexture(), material.getEmissiveTextureInfo(), `${at}/emissiveTexture`);

  const ext = (name: string): string => `${at}/extensions/${name}`;
  const emissive = material.getExtension<EmissiveStrength>('KHR_materials_emissive_strength');
  if (emissive) out.emissiveStrength = emissive.getEmissiveStrength();
  const ior = material.getExtension<IOR>('KHR_materials_ior');
  if (ior) out.ior = ior.getIOR();

  const specular = material.getExtension<Specular>('KHR_materials_specular');
  if (specular) {
    const e = ext('KHR_materials_specular');
    out.specularFactor = specular.getSpecularFactor();
    out.specularColorFactor = [...specular.getSpecularColorFactor()];
    await slot('specularTexture', specular.getSpecularTexture(), specular.getSpecularTextureInfo(), `${e}/specularTexture`);
    await slot('specularColorTexture', specular.getSpecularColorTexture(), specular.getSpecularColorTextureInfo(), `${e}/specularColorTexture`);
  }
  const transmission = material.getExtension<Transmission>('KHR_materials_transmission');
  if (transmission) {
    out.transmissionFactor = transmission.getTransmissionFactor();
    await slot('transmissionTexture', transmission.getTransmissionTexture(), transmission.getTransmissionTextureInfo(), `${ext('KHR_materials_transmission')}/transmissionTexture`);
  }
  const volume = material.getExtension<Volume>('KHR_materials_volume');
  if (volume) {
    out.thicknessFactor = volume.getThicknessFactor();
    out.attenuationColor = [...volume.getAttenuationColor()];
    out.attenuationDistance = volume.getAttenuationDistance();
    await slot('thicknessTexture', volume.getThicknessTexture(), volume.getThicknessTextureInfo(), `${ext('KHR_materials_volume')}/thicknessTexture`);
  }
  const clearcoat = material.getExtension<Clearcoat>('KHR_materials_clearcoat');
  if (clearcoat) {
    const e = ext('KHR_materials_clearcoat');
    out.clearcoatFactor = clearcoat.getClearcoatFactor();
    out.clearcoatRoughnessFactor = clearcoat.getClearcoatRoughnessFactor();
    await slot('clearcoatTexture', clearcoat.getClearcoatTexture(), clearcoat.getClearcoatTextureInfo(), `${e}/clearcoatTexture`);
    await slot('clearcoatRoughnessTexture', clearcoat.getClearcoatRoughnessTexture(), clearcoat.getClearcoatRoughnessTextureInfo(), `${e}/clearcoatRoughnessTexture`);
    await slot('clearcoatNormalTexture', clearcoat.getClearcoatNormalTexture(), clearcoat.getClearcoatNormalTextureInfo(), `${e}/clearcoatNormalTexture`, { scale: clearcoat.getClearcoatNormalScale() });
  }
  const sheen = material.getExtension<Sheen>('KHR_materials_sheen');
  if (sheen) {
    const e = ext('KHR_materials_sheen');
    out.sheenColorFactor = [...sheen.getSheenColorFactor()];
    out.sheenRoughnessFactor = sheen.getSheenRoughnessFactor();
    await slot('sheenColorTexture', sheen.getSheenColorTexture(), sheen.getSheenColorTextureInfo(), `${e}/sheenColorTexture`);
    await slot('sheenRoughnessTexture', sheen.getSheenRoughnessTexture(), sheen.getSheenRoughnessTextureInfo(), `${e}/sheenRoughnessTexture`);
  }
  const dispersion = material.getExtension<Dispersion>('KHR_materials_dispersion');
  if (dispersion) out.dispersion = dispersion.getDispersion();
  const iridescence = material.getExtension<Iridescence>('KHR_materials_iridescence');
  if (iridescence) {
    const e = ext('KHR_materials_iridescence');
    out.iridescenceFactor = iridescence.getIridescenceFactor();
    out.iridescenceIor = iridescence.getIridescenceIOR();
    out.iridescenceThicknessMinimum = iridescence.getIridescenceThicknessMinimum();
    out.iridescenceThicknessMaximum = iridescence.getIridescenceThicknessMaximum();
    await slot('iridescenceTexture', iridescence.getIridescenceTexture(), iridescence.getIridescenceTextureInfo(), `${e}/iridescenceTexture`);
    await slot('iridescenceThicknessTexture', iridescence.getIridescenceThicknessTexture(), iridescence.getIridescenceThicknessTextureInfo(), `${e}/iridescenceThicknessTexture`);
  }
  const anisotropy = material.getExtension<Anisotropy>('KHR_materials_anisotropy');
  if (anisotropy) {
    out.anisotropyStrength = anisotropy.getAnisotropyStrength();
    out.anisotropyRotation = anisotropy.getAnisotropyRotation();
    await slot('anisotropyTexture', anisotropy.getAnisotropyTexture(), anisotropy.getAnisotropyTextureInfo(), `${ext('KHR_materials_anisotropy')}/anisotropyTexture`);
  }
  const specGloss = material.getExtension<PBRSpecularGlossiness>('KHR_materials_pbrSpecularGlossiness');
  if (specGloss) await applySpecularGlossiness(out, specGloss, ext('KHR_materials_pbrSpecularGlossiness'), table);
  const diffuse = material.getExtension<DiffuseTransmission>('KHR_materials_diffuse_transmission');
  if (diffuse) {
    const e = ext('KHR_materials_diffuse_transmission');
    out.diffuseTransmissionFactor = diffuse.getDiffuseTransmissionFactor();
    out.diffuseTransmissionColorFactor = [...diffuse.getDiffuseTransmissionColorFactor()];
    await slot('diffuseTransmissionTexture', diffuse.getDiffuseTransmissionTexture(), diffuse.getDiffuseTransmissionTextureInfo(), `${e}/diffuseTransmissionTexture`);
    await slot('diffuseTransmissionColorTexture', diffuse.getDiffuseTransmissionColorTexture(), diffuse.getDiffuseTransmissionColorTextureInfo(), `${e}/diffuseTransmissionColorTexture`);
  }
  if (material.getExtension<Unlit>('KHR_materials_unlit')) makeUnlit(out);
  return out;
}

/**
 * KHR_materials_pbrSpecularGlossiness as metallic-roughness with KHR_materials_specular (the
 * conversion glTF-Transform's `metalRough` makes): diffuse becomes the base colour of a dielectric
 * (metallic 0), the specular colour becomes the F0 colour (specularColorFactor and
 * specularColorTexture, with ior 0, KHR_materials_ior's specular-glossiness mode where the Fresnel
 * term reaches that colour at normal incidence) and roughness is 1 - glossiness, baked per texel
 * into a roughness image when the glossiness comes from the texture's alpha.
 */
async function applySpecularGlossiness(out: WavefrontMaterialInput, specGloss: PBRSpecularGlossiness, at: string, table: TextureTable): Promise<void> {
  const glossiness = specGloss.getGlossinessFactor();
  out.baseColorFactor = [...specGloss.getDiffuseFactor()];
  delete out.baseColorTexture;
  delete out.metallicRoughnessTexture;
  const diffuseTexture = await table.reference(specGloss.getDiffuseTexture(), specGloss.getDiffuseTextureInfo(), `${at}/diffuseTexture`);
  if (diffuseTexture !== undefined) out.baseColorTexture = diffuseTexture;
  out.metallicFactor = 0;
  out.roughnessFactor = 1 - glossiness;
  out.ior = 0;
  out.specularFactor = 1;
  out.specularColorFactor = [...specGloss.getSpecularFactor()];
  delete out.specularTexture;
  delete out.specularColorTexture;
  const sgAt = `${at}/specularGlossinessTexture`;
  const sgTexture = specGloss.getSpecularGlossinessTexture();
  const sgInfo = specGloss.getSpecularGlossinessTextureInfo();
  const specularColor = await table.reference(sgTexture, sgInfo, sgAt);
  if (specularColor === undefined) return;
  out.specularColorTexture = specularColor;
  const roughness = await table.derivedReference(sgTexture, sgInfo, sgAt, `roughness from glossiness x ${glossiness}`, (image) => roughnessFromGlossiness(image, glossiness));
  if (roughness !== undefined) {
    out.metallicRoughnessTexture = roughness;
    out.roughnessFactor = 1;
  }
}

/**
 * A metallic-roughness image (G = roughness, B = metallic = 0) of a specular-glossiness texture:
 * roughness = 1 - glossinessFactor * alpha, both linear.
 */
export function roughnessFromGlossiness(image: WavefrontImageInput, glossinessFactor: number): WavefrontImageInput {
  const data = new Uint8Array(image.width * image.height * 4);
  for (let p = 0; p < data.length; p += 4) {
    data[p + 1] = Math.round(255 * (1 - (glossinessFactor * image.data[p + 3]!) / 255));
    data[p + 3] = 255;
  }
  return { width: image.width, height: image.height, data };
}

/**
 * KHR_materials_unlit as the physical surface it describes: one that emits its base colour (factor,
 * texture; alpha kept for blending and masking) and scatters nothing (black base colour, no
 * specular reflection, no transmission). Under light it shows exactly its base colour, and it
 * lights its surroundings as any emitter does.
 */
function makeUnlit(out: WavefrontMaterialInput): void {
  const [r, g, b] = out.baseColorFactor ?? [1, 1, 1];
  const a = out.baseColorFactor?.[3] ?? 1;
  out.emissiveFactor = [r!, g!, b!];
  out.emissiveStrength = 1;
  if (out.baseColorTexture !== undefined) out.emissiveTexture = out.baseColorTexture;
  else delete out.emissiveTexture;
  out.baseColorFactor = [0, 0, 0, a];
  out.metallicFactor = 0;
  out.roughnessFactor = 1;
  out.specularFactor = 0;
  for (const key of ['metallicRoughnessTexture', 'normalTexture', 'occlusionTexture', 'specularTexture', 'specularColorTexture', 'transmissionFactor', 'transmissionTexture', 'clearcoatFactor', 'sheenColorFactor', 'iridescenceFactor', 'diffuseTransmissionFactor'] as const) {
    delete out[key];
  }
}

/** The glTF default material (section 3.9.6): every property at its default. */
export function defaultGltfMaterial(): WavefrontMaterialInput {
  return { name: 'glTF default material', baseColorFactor: [1, 1, 1, 1], metallicFactor: 1, roughnessFactor: 1, emissiveFactor: [0, 0, 0], alphaMode: 'OPAQUE', doubleSided: false };
}
