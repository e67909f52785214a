// The material extension registry is the one description every consumer reads: these tests check
// that its entries are consistent with each other and with the GPU layout, and that normalization,
// the scene-file reader, the packer and the raster renderer follow each entry.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { GpuRendererError } from '../../../src/errors/index.ts';
import {
  MATERIAL_ALPHA_MODE_MASK,
  MATERIAL_EXTENSION_MASK,
  MATERIAL_FLAG_DOUBLE_SIDED,
  MATERIAL_FLAG_ENERGY_COMPENSATION,
  MATERIAL_FLAG_IOR_INFINITE,
  gpuConstants,
} from '../../../src/gpu-layout/constants.ts';
import { heapRecordLayouts, materialCoreLayout, surfaceRecordLayout } from '../../../src/gpu-layout/records.ts';
import { anyMaterialExtensions, type FactorSpec, type MaterialExtensionSpec } from '../../../src/materials/extensions/index.ts';
import { materialLayerReferences } from '../../../src/materials/material-layers.generated.ts';
import { planMaterials } from '../../../src/pathtracer/scene/pack-materials.ts';
import { materialFeatures } from '../../../src/pathtracer/scene/material-features.ts';
import { normalizeRasterMaterial } from '../../../src/raster/scene/raster-material.ts';
import { normalizeMaterial } from '../../../src/scene/material.ts';
import { validateSceneDescription } from '../../../src/scene/scene-file.ts';
import type { WavefrontMaterialInput } from '../../../src/scene/types.ts';
import { shaderFeatures } from '../../../src/shaders/features.ts';

const extensions: readonly MaterialExtensionSpec<never>[] = anyMaterialExtensions;

/** A value inside the factor's range and off its default. */
function inRange(f: FactorSpec): number | number[] {
  const lo = f.range.min ?? f.range.above ?? -1;
  const hi = f.range.max ?? lo + 2;
  const v = lo + 0.375 * (hi - lo) + (f.range.above !== undefined ? 0.5 : 0);
  return f.type === 'rgb' ? [v, v * 0.5 + 0.25 * hi, hi] : v;
}

/** Material input turning every extension on (factors in range, all off their defaults). */
function everyExtensionOn(): Record<string, unknown> {
  const m: Record<string, unknown> = {};
  for (const e of extensions) for (const f of e.factors) m[f.key] = inRange(f);
  return m;
}

test('registry entries: unique names, keys, flag bits and feature constants, clear of the core flags', () => {
  const unique = (values: unknown[], what: string): void => assert.equal(new Set(values).size, values.length, `duplicate ${what}`);
  unique(extensions.map((e) => e.name), 'extension name');
  unique(extensions.map((e) => e.key), 'normalized key');
  unique(extensions.flatMap((e) => [...e.factors.map((f) => f.key), ...e.textures.map((t) => t.key)]), 'material input key');
  unique(extensions.map((e) => e.flag.bit), 'flag bit');
  unique(extensions.map((e) => e.feature.name), 'feature constant');
  const core = MATERIAL_FLAG_DOUBLE_SIDED | MATERIAL_ALPHA_MODE_MASK | MATERIAL_FLAG_ENERGY_COMPENSATION | MATERIAL_FLAG_IOR_INFINITE;
  for (const e of extensions) {
    const bit = 1 << e.flag.bit;
    assert.equal(bit & core, 0, `${e.name}: flag bit ${e.flag.bit} overlaps a core material flag`);
    assert.equal(bit & MATERIAL_EXTENSION_MASK, bit, `${e.name}: flag outside MATERIAL_EXTENSION_MASK`);
    assert.equal((gpuConstants as Record<string, number>)[e.flag.name], bit, `${e.flag.name} is not the generated WGSL constant`);
    assert.ok(e.feature.name in shaderFeatures, `${e.feature.name} is not a shader feature`);
    assert.ok(e.factors.some((f) => f.key === e.enabledBy), `${e.name}: enabledBy names none of its factors`);
  }
});

test('registry entries: every block is a materials-heap record and MaterialCore holds its offset', () => {
  const heapNames = heapRecordLayouts.materials.map((l) => l.name);
  for (const e of extensions) {
    if (!e.block) continue;
    assert.ok(heapNames.includes(e.block.layout.name), `${e.block.layout.name} gets no heap loader`);
    const field = materialCoreLayout.fields.find((f) => f.name === e.key);
    assert.equal(field?.scalar, 'u32', `MaterialCore.${e.key} (the ${e.block.layout.name} offset) is missing`);
  }
});

test('normalization follows each entry: factors land in their block fields, out-of-range values are refused naming the key', () => {
  const m = normalizeMaterial(everyExtensionOn() as WavefrontMaterialInput, 'materials[0]') as unknown as Record<string, unknown>;
  for (const e of extensions) {
    const block = m[e.key];
    assert.notEqual(block, undefined, `${e.name} should be present with every factor off its default`);
    for (const f of e.factors) {
      const got = e.normalized === 'scalar' ? block : (block as Record<string, unknown>)[f.field];
      assert.deepEqual(got, inRange(f), `${e.name}.${f.field}`);
    }
  }
  for (const e of extensions) {
    for (const f of e.factors) {
      const bad = f.range.max !== undefined ? f.range.max + 0.5 : (f.range.min ?? f.range.above) !== undefined ? (f.range.min ?? f.range.above)! - 0.5 : undefined;
      if (bad === undefined) continue;
      const value = f.type === 'rgb' ? [0.5, 0.5, bad] : bad;
      const field = f.type === 'rgb' ? `materials[1].${f.key}[2]` : `materials[1].${f.key}`;
      assert.throws(
        () => normalizeMaterial({ [f.key]: value } as WavefrontMaterialInput, 'materials[1]'),
        (err: unknown) => err instanceof GpuRendererError && err.code === 'INVALID_MATERIAL' && err.field === field,
        `${f.key} = ${JSON.stringify(value)} should be refused naming ${field}`,
      );
    }
  }
});

test('scene files accept every registry key, the plan turns on each extension\'s feature, the raster renderer refuses what it does not draw', () => {
  const material = everyExtensionOn();
  const file = validateSceneDescription({ materials: [material] });
  assert.deepEqual(Object.keys(file.materials![0]!).sort(), Object.keys(material).sort());
  const plan = planMaterials([normalizeMaterial(material as WavefrontMaterialInput, 'materials[0]')]);
  const features = materialFeatures(plan.uses) as Record<string, boolean>;
  for (const e of extensions) assert.equal(features[e.feature.name], true, e.feature.name);
  for (const e of extensions) {
    // Dispersion is present only on a refractive solid, whose transmission the raster renderer
    // takes out of the shared normalization (it draws it itself), so it never meets it.
    if (e.key === 'dispersion') continue;
    const alone: Record<string, unknown> = { [e.enabledBy]: inRange(e.factors.find((f) => f.key === e.enabledBy)!) };
    if (e.key === 'volume') Object.assign(alone, { transmissionFactor: 1 });
    const draw = (): unknown => normalizeRasterMaterial(alone as WavefrontMaterialInput, 'materials[2]', 0);
    if (e.raster === 'drawn') assert.doesNotThrow(draw, e.name);
    else assert.throws(draw, (err: unknown) => err instanceof GpuRendererError && err.field === `materials[2].${e.enabledBy}`, e.name);
  }
});

test('layers: every registry entry with a layer has its CPU reference in the composed stack, in registry order, with its flag, feature and surface-record words', () => {
  const layered = extensions.filter((e) => e.layer !== undefined);
  assert.ok(layered.length > 0);
  assert.deepEqual(
    materialLayerReferences.map((r) => r.key),
    layered.map((e) => e.key),
  );
  for (const [k, e] of layered.entries()) {
    const reference = materialLayerReferences[k]!;
    assert.equal(reference.flag, gpuConstants[e.flag.name], `${e.name}: the reference's flag`);
    assert.equal(reference.feature, e.feature.name, `${e.name}: the reference's feature`);
    assert.ok(surfaceRecordLayout.fields.some((f) => f.name === `${e.key}Layer`), `${e.name}: its SurfaceRecord words`);
    assert.ok(reference.examples.length > 0, `${e.name}: examples for the composed-BSDF harness`);
    for (const example of reference.examples) assert.ok(reference.pack(example.value as never).length <= 8, `${e.name}: packs into its two vec4s`);
  }
  assert.equal(gpuConstants.PACKED_LAYER_VEC4S, 2 * layered.length);
});
