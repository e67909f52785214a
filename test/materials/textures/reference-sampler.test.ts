import assert from 'node:assert/strict';
import { test } from 'node:test';
import {
  SAMPLER_MAG_LINEAR,
  SAMPLER_MIN_LINEAR,
  SAMPLER_MIP_LINEAR,
  SAMPLER_MIPMAPS,
  SAMPLER_WRAP_CLAMP,
  SAMPLER_WRAP_MIRROR,
  SAMPLER_WRAP_REPEAT,
  SAMPLER_WRAP_S_SHIFT,
  SAMPLER_WRAP_T_SHIFT,
  TEXTURE_BINDING_FLAG_SRGB,
} from '../../../src/gpu-layout/constants.ts';
import { textureBindingLayout } from '../../../src/gpu-layout/records.ts';
import { Vec4Heap } from '../../../src/gpu-layout/vec4-heap.ts';
import { sampleBoundTexture, sampleTextureInfo, textureLod, type Rgba, type TextureBindingRecord } from '../../../src/materials/textures/reference-sampler.ts';
import { textureTransformMatrix } from '../../../src/scene/texture-transform.ts';
import { buildTextureAtlas } from '../../../src/materials/textures/texture-atlas.ts';
import type { WavefrontTextureTransformInput } from '../../../src/scene/types.ts';
import { rng } from '../../helpers/random.ts';
import { constantLevel, handAtlas } from './atlas-fixtures.ts';

const decode = (c: number): number => (c <= 0.04045 ? c / 12.92 : ((c + 0.055) / 1.055) ** 2.4);
const wrap = (s: number, t: number): number => (s << SAMPLER_WRAP_S_SHIFT) | (t << SAMPLER_WRAP_T_SHIFT);

function near(got: readonly number[], want: readonly number[], tol: number, label: string): void {
  got.forEach((v, i) => assert.ok(Math.abs(v - want[i]!) <= tol, `${label}: got [${got.map((x) => x.toFixed(6))}], want [${want.map((x) => x.toFixed(6))}]`));
}

function randomLevel(w: number, h: number, seed: number): Uint8Array {
  const next = rng(seed);
  return Uint8Array.from({ length: w * h * 4 }, () => Math.floor(next() * 256));
}

const texel = (level: Uint8Array, w: number, x: number, y: number, srgb: boolean): Rgba => {
  const at = (y * w + x) * 4;
  const v = [0, 1, 2, 3].map((c) => level[at + c]! / 255);
  return (srgb ? [decode(v[0]!), decode(v[1]!), decode(v[2]!), v[3]!] : v) as Rgba;
};

test('nearest at texel centres returns the texel (decoded when sRGB)', () => {
  const [w, h] = [5, 3];
  const level = randomLevel(w, h, 1);
  const { atlas, info } = handAtlas(w, h, [level], 0);
  for (const srgb of [false, true]) {
    for (let y = 0; y < h; y++) {
      for (let x = 0; x < w; x++) near(sampleTextureInfo(atlas, info, [(x + 0.5) / w, (y + 0.5) / h], 0, srgb), texel(level, w, x, y, srgb), 1e-7, `${x},${y}`);
    }
  }
});

test('bilinear at the midpoint of two texels is their mean (in linear light when sRGB)', () => {
  const [w, h] = [6, 4];
  const level = randomLevel(w, h, 2);
  const { atlas, info } = handAtlas(w, h, [level], SAMPLER_MAG_LINEAR);
  for (const srgb of [false, true]) {
    for (let y = 0; y < h; y++) {
      for (let x = 0; x + 1 < w; x++) {
        const a = texel(level, w, x, y, srgb);
        const b = texel(level, w, x + 1, y, srgb);
        near(sampleTextureInfo(atlas, info, [(x + 1) / w, (y + 0.5) / h], 0, srgb), a.map((v, c) => (v + b[c]!) / 2), 1e-6, `horizontal ${x},${y}`);
      }
    }
    // Vertical neighbours too.
    const a = texel(level, w, 3, 1, srgb);
    const b = texel(level, w, 3, 2, srgb);
    near(sampleTextureInfo(atlas, info, [3.5 / w, 2 / h], 0, srgb), a.map((v, c) => (v + b[c]!) / 2), 1e-6, 'vertical');
  }
});

test('wrap modes on a 4x1 ramp at u = -0.1, 1.1, 2.3 (OpenGL 4.6 section 8.14.2)', () => {
  const ramp = Uint8Array.from([0, 85, 170, 255].flatMap((v) => [v, v, v, 255]));
  const value = (i: number): number => [0, 85, 170, 255][i]! / 255;
  // Texel indices by hand. Nearest: i = floor(4u) = -1, 4, 9. Repeat: i mod 4 -> 3, 0, 1. Clamp: 0, 3, 3.
  // Mirrored repeat (period 8, second half reversed): -1 -> 0, 4 -> 3, 9 -> 1.
  // Linear: p = 4u - 1/2 = -0.9, 3.9, 8.7 -> i0 = -1, 3, 8 with weights 0.1, 0.9, 0.7 on i0 + 1.
  const cases = [
    { mode: SAMPLER_WRAP_REPEAT, nearest: [3, 0, 1], linear: [[3, 0], [3, 0], [0, 1]] },
    { mode: SAMPLER_WRAP_CLAMP, nearest: [0, 3, 3], linear: [[0, 0], [3, 3], [3, 3]] },
    { mode: SAMPLER_WRAP_MIRROR, nearest: [0, 3, 1], linear: [[0, 0], [3, 3], [0, 1]] },
  ];
  const us = [-0.1, 1.1, 2.3];
  const weights = [0.1, 0.9, 0.7];
  for (const { mode, nearest, linear } of cases) {
    const n = handAtlas(4, 1, [ramp], wrap(mode, SAMPLER_WRAP_CLAMP));
    const l = handAtlas(4, 1, [ramp], wrap(mode, SAMPLER_WRAP_CLAMP) | SAMPLER_MAG_LINEAR);
    us.forEach((u, k) => {
      assert.ok(Math.abs(sampleTextureInfo(n.atlas, n.info, [u, 0.5], 0, false)[0] - value(nearest[k]!)) < 1e-9, `mode ${mode} nearest u=${u}`);
      const [i0, i1] = linear[k]!;
      const want = value(i0!) * (1 - weights[k]!) + value(i1!) * weights[k]!;
      assert.ok(Math.abs(sampleTextureInfo(l.atlas, l.info, [u, 0.5], 0, false)[0] - want) < 1e-6, `mode ${mode} linear u=${u}`);
    });
  }
});

test('mip selection: magnification at lod <= 0, nearest level by the OpenGL rule, trilinear blend, clamp to the last level', () => {
  // Levels of constant, unrelated colours, so every lookup shows which levels it read.
  const levels = [constantLevel(4, 4, [200, 0, 0, 255]), constantLevel(2, 2, [0, 100, 0, 255]), constantLevel(1, 1, [0, 0, 60, 255])];
  const colour = levels.map((l) => [l[0]! / 255, l[1]! / 255, l[2]! / 255, 1]);
  const blend = (a: number, b: number, t: number): number[] => colour[a]!.map((v, c) => v * (1 - t) + colour[b]![c]! * t);
  const trilinear = handAtlas(4, 4, levels, SAMPLER_MAG_LINEAR | SAMPLER_MIN_LINEAR | SAMPLER_MIPMAPS | SAMPLER_MIP_LINEAR);
  const nearestMip = handAtlas(4, 4, levels, SAMPLER_MIN_LINEAR | SAMPLER_MIPMAPS);
  const noMips = handAtlas(4, 4, levels, SAMPLER_MIN_LINEAR);
  const uv: [number, number] = [0.3, 0.6];
  const at = (h: ReturnType<typeof handAtlas>, lod: number) => sampleTextureInfo(h.atlas, h.info, uv, lod, false);
  near(at(trilinear, 0), colour[0]!, 1e-7, 'lod 0 magnifies');
  near(at(trilinear, -3), colour[0]!, 1e-7, 'lod -3 magnifies');
  near(at(trilinear, 0.25), blend(0, 1, 0.25), 1e-7, 'lod 0.25');
  near(at(trilinear, 1.5), blend(1, 2, 0.5), 1e-7, 'halfway between levels 1 and 2');
  near(at(trilinear, 7), colour[2]!, 1e-7, 'past the last level');
  // OpenGL 4.6 section 8.14.3: level 0 up to lambda = 1/2, then ceil(lambda + 1/2) - 1 (ties go down).
  for (const [lod, level] of [[0.5, 0], [0.51, 1], [1.5, 1], [1.51, 2], [2.5, 2], [9, 2]] as const) near(at(nearestMip, lod), colour[level]!, 1e-7, `nearest mip at lod ${lod}`);
  near(at(noMips, 2), colour[0]!, 1e-7, 'minFilter linear reads level 0 only');
});

function bindingHeap(transform: WavefrontTextureTransformInput, texture: number, texCoord: number, srgb: boolean, heap: Vec4Heap): number {
  return heap.append(textureBindingLayout, { ...textureTransformMatrix(transform), texture, texCoord, scale: 1, flags: srgb ? TEXTURE_BINDING_FLAG_SRGB : 0 });
}

test('KHR_texture_transform offset, rotation and scale move a known texel to the expected uv', () => {
  // A 4x4 texture with a distinct value per texel (r = 16 * index), nearest filtering, repeat.
  const data = Uint8Array.from({ length: 64 }, (_, i) => (i % 4 === 0 ? 16 * (i / 4) : i % 4 === 3 ? 255 : 0));
  const heap = new Vec4Heap();
  const atlas = buildTextureAtlas({ textures: [{ image: { width: 4, height: 4, data }, sampler: { magFilter: 'nearest', minFilter: 'nearest' } }] }, [{ texture: 0, srgb: false }], heap, {
    maxTextureDimension2D: 64,
    maxTextureArrayLayers: 4,
  });
  const info = atlas.infoOffset(0, false);
  const noFootprint = { widthOverCos: 0, worldArea: 0, uvArea: [0, 0] as [number, number] };
  // [transform, input uv, texel (x, y) by hand]
  const cases: [WavefrontTextureTransformInput, [number, number], [number, number]][] = [
    [{}, [0.1, 0.6], [0, 2]],
    [{ offset: [0.25, 0.5] }, [0.1, 0.1], [1, 2]], // (0.35, 0.6)
    [{ scale: [2, 3] }, [0.1, 0.1], [0, 1]], // (0.2, 0.3)
    [{ rotation: Math.PI / 2 }, [0.1, 0.2], [0, 3]], // R (0.1, 0.2) = (0.2, -0.1) -> repeat (0.2, 0.9)
    [{ offset: [0, 1], rotation: Math.PI / 2, scale: [0.5, 0.5] }, [0.1, 0.1], [0, 3]], // (0.05, 0.95): lower left
    [{ offset: [0, 1], rotation: Math.PI / 2, scale: [0.5, 0.5] }, [0.9, 0.1], [0, 2]], // (0.05, 0.55)
    [{ offset: [0, 1], rotation: Math.PI / 2, scale: [0.5, 0.5] }, [0.1, 0.9], [1, 3]], // (0.45, 0.95)
  ];
  for (const [transform, uv, [x, y]] of cases) {
    for (const texCoord of [0, 1]) {
      const b = bindingHeap(transform, info, texCoord, false, heap);
      const bytes = heap.finish();
      const [uv0, uv1]: [number, number][] = texCoord === 0 ? [uv, [0.99, 0.99]] : [[0.99, 0.99], uv];
      const got = sampleBoundTexture(atlas, bytes, b, uv0, uv1, noFootprint);
      assert.equal(Math.round(got[0] * 255), 16 * (y * 4 + x), `${JSON.stringify(transform)} at ${uv} (set ${texCoord})`);
    }
  }
});

test('ray-cone LOD: log2(width / cos) + 0.5 log2(texel area / world area), scaled by the uv transform', () => {
  const info = { origin: [0, 0], size: [64, 64], layer: 0, mipCount: 7, sampler: 0 } as const;
  const binding = (t: WavefrontTextureTransformInput, texCoord = 0): TextureBindingRecord => ({ ...textureTransformMatrix(t), texture: 0, texCoord, scale: 1, flags: 0 });
  const f = { widthOverCos: 0.25, worldArea: 2, uvArea: [0.5, 0.125] as [number, number] };
  // texel area = 0.5 * 64 * 64 = 2048; lambda = log2(0.25) + 0.5 log2(2048 / 2) = -2 + 5.
  assert.ok(Math.abs(textureLod(binding({}), info, f) - 3) < 1e-12);
  // Scale 2 in both axes quadruples the texel area: one level up.
  assert.ok(Math.abs(textureLod(binding({ scale: [2, 2], rotation: 0.7 }), info, f) - 4) < 1e-12);
  // uv set 1 has a quarter of the area: one level down.
  assert.ok(Math.abs(textureLod(binding({}, 1), info, f) - 2) < 1e-12);
  // No footprint (primary rays without cones, degenerate triangles): level 0.
  assert.equal(textureLod(binding({}), info, { ...f, worldArea: 0 }), 0);
  assert.equal(textureLod(binding({ scale: [0, 1] }), info, f), 0);
});

test('sampleBoundTexture decodes sRGB per the binding flag', () => {
  const data = Uint8Array.from([128, 64, 32, 200]);
  const heap = new Vec4Heap();
  const atlas = buildTextureAtlas({ textures: [{ image: { width: 1, height: 1, data } }] }, [{ texture: 0, srgb: true }], heap, { maxTextureDimension2D: 16, maxTextureArrayLayers: 1 });
  const b = bindingHeap({}, atlas.infoOffset(0, true), 0, true, heap);
  const got = sampleBoundTexture(atlas, heap.finish(), b, [0.5, 0.5], [0, 0], { widthOverCos: 0, worldArea: 0, uvArea: [0, 0] });
  near(got, [decode(128 / 255), decode(64 / 255), decode(32 / 255), 200 / 255], 1e-12, 'sRGB texel');
});
