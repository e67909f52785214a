/**
 * glTF materials -> WavefrontMaterialInput: the core metallic-roughness factors and textures
 * (glTF 2.0 section 3.9) and the KHR_materials_* extensions' factors and textures under their glTF
 * names (each extension's registry entry, materials/extensions/, lists them). Extension factors are written only for materials that carry the extension, so a missing
 * one keeps the renderer's (the extension's) default.
 */
import type { ExtensionProperty, Material, Texture, TextureInfo } from '@gltf-transform/core';
import type { EmissiveStrength, IOR, PBRSpecularGlossiness, Unlit } from '@gltf-transform/extensions';
import { anyMaterialExtensions, type MaterialExtensionSpec } from '../../materials/extensions/index.ts';
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

  for (const e of anyMaterialExtensions) {
    const x = material.getExtension<ExtensionProperty>(e.name);
    if (x) await mapExtension(e, x as unknown as Getters, ext(e.name), out, slot);
  }
  const specGloss = material.getExtension<PBRSpecularGlossiness>('KHR_materials_pbrSpecularGlossiness');
  if (specGloss) await applySpecularGlossiness(out, specGloss, ext('KHR_materials_pbrSpecularGlossiness'), table);
  if (material.getExtension<Unlit>('KHR_materials_unlit')) makeUnlit(out);
  return out;
}

/** @gltf-transform's extension properties, read through the getters their registry entries name. */
type Getters = Record<string, () => unknown>;
type SlotWriter = (name: Slot, texture: Texture | null, info: TextureInfo | null, slotAt: string, extra?: Partial<WavefrontTextureRefInput>) => Promise<void>;

function capitalized(key: string): string {
  return key[0]!.toUpperCase() + key.slice(1);
}

/**
 * One KHR material extension's factors and textures under their glTF names (the registry entry
 * lists them; @gltf-transform reads each with `get<Name>()` and `get<Name>Info()`).
 */
async function mapExtension(e: MaterialExtensionSpec<never>, x: Getters, at: string, out: WavefrontMaterialInput, slot: SlotWriter): Promise<void> {
  const o = out as Record<string, unknown>;
  for (const f of e.factors) {
    const value = x[f.getter ?? `get${capitalized(f.key)}`]!.call(x);
    o[f.key] = Array.isArray(value) ? [...(value as number[])] : value;
  }
  for (const t of e.textures) {
    const name = capitalized(t.key);
    const extra = t.scaleGetter === undefined ? undefined : { scale: x[t.scaleGetter]!.call(x) as number };
    await slot(t.key as Slot, x[`get${name}`]!.call(x) as Texture | null, x[`get${name}Info`]!.call(x) as TextureInfo | null, `${at}/${t.key}`, extra);
  }
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
