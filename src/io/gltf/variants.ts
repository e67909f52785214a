/**
 * KHR_materials_variants: named material sets. A selected variant replaces each primitive's
 * material with the one its mapping list names for that variant; primitives without a mapping for
 * it keep their default material (extension spec, "Variant Selection").
 */
import type { Document, Material, Primitive } from '@gltf-transform/core';
import type { KHRMaterialsVariants, MappingList, Variant } from '@gltf-transform/extensions';
import { GpuRendererError } from '../../errors/gpu-renderer-error.ts';

function variantExtension(document: Document): KHRMaterialsVariants | undefined {
  return document.getRoot().listExtensionsUsed().find((e) => e.extensionName === 'KHR_materials_variants') as KHRMaterialsVariants | undefined;
}

export function listVariants(document: Document): Variant[] {
  return variantExtension(document)?.listVariants() ?? [];
}

/** The variant named `name`; an unknown name is an INVALID_OPTION error naming the known ones. */
export function selectVariant(document: Document, name: string | undefined): Variant | undefined {
  if (name === undefined) return undefined;
  const variants = listVariants(document);
  const variant = variants.find((v) => v.getName() === name);
  if (variant === undefined) {
    const known = variants.map((v) => JSON.stringify(v.getName())).join(', ');
    throw new GpuRendererError('INVALID_OPTION', `unknown KHR_materials_variants variant ${JSON.stringify(name)} (the asset has ${known === '' ? 'none' : known})`, { field: 'variant' });
  }
  return variant;
}

/** The primitive's material under `variant`, or its default material. */
export function variantMaterial(primitive: Primitive, variant: Variant | undefined): Material | null {
  if (variant !== undefined) {
    const mappings = primitive.getExtension<MappingList>('KHR_materials_variants');
    const mapping = mappings?.listMappings().find((m) => m.listVariants().includes(variant));
    if (mapping !== undefined) return mapping.getMaterial();
  }
  return primitive.getMaterial();
}
