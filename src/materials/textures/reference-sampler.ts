/**
 * CPU mirror of texture-sampling.wesl, function for function: per-texture wrap modes on texel
 * indices, nearest or bilinear filtering with textureLoad-style reads from the packed atlas, sRGB
 * decoding of every texel before filtering, mip selection (OpenGL 4.6 section 8.14.3) and the
 * trilinear blend, KHR_texture_transform and the ray-cone level of detail. It is the reference the
 * GPU tests compare against and a tool for debugging atlases on the CPU.
 *
 * Texel coordinates are computed in f32 (Math.fround after every operation, as WGSL's correctly
 * rounded f32 arithmetic does), so the reference picks exactly the texels the GPU picks; filter
 * weights and colours are then evaluated in f64.
 */
import { srgbToLinear } from '../../color/srgb.ts';
import {
  SAMPLER_MAG_LINEAR,
  SAMPLER_MIN_LINEAR,
  SAMPLER_MIP_LINEAR,
  SAMPLER_MIPMAPS,
  SAMPLER_WRAP_CLAMP,
  SAMPLER_WRAP_MIRROR,
  SAMPLER_WRAP_S_SHIFT,
  SAMPLER_WRAP_T_SHIFT,
  TEXTURE_BINDING_FLAG_SRGB,
} from '../../gpu-layout/constants.ts';
import { textureBindingLayout, textureInfoLayout } from '../../gpu-layout/records.ts';
import { readStruct } from '../../gpu-layout/struct-layout.ts';
import type { Vec3Row } from '../../scene/texture-transform.ts';

export type Rgba = [number, number, number, number];

/** The packed atlas texels (a TextureAtlas will do). */
export interface AtlasTexels {
  readonly layerSize: number;
  readonly layers: readonly Uint8Array[];
}

/** A TextureInfo record (records.ts). */
export interface TextureInfoRecord {
  readonly origin: readonly [number, number];
  readonly size: readonly [number, number];
  readonly layer: number;
  readonly mipCount: number;
  readonly sampler: number;
}

/** A TextureBinding record (records.ts). */
export interface TextureBindingRecord {
  readonly transform0: Readonly<Vec3Row>;
  readonly transform1: Readonly<Vec3Row>;
  readonly texture: number;
  readonly texCoord: number;
  readonly scale: number;
  readonly flags: number;
}

/** texture-sampling.wesl `TextureFootprint`. */
export interface TextureFootprint {
  readonly widthOverCos: number;
  readonly worldArea: number;
  readonly uvArea: readonly [number, number];
}

const f32 = Math.fround;

function heapView(heap: ArrayBuffer, offset: number, size: number): DataView {
  return new DataView(heap, offset * 16, size);
}

/** The TextureInfo at vec4 `offset` of a materials heap (Vec4Heap.finish()). */
export function readTextureInfo(heap: ArrayBuffer, offset: number): TextureInfoRecord {
  const r = readStruct(textureInfoLayout, heapView(heap, offset, textureInfoLayout.size), 0);
  const [ox, oy] = r.origin as number[];
  const [w, h] = r.size as number[];
  return { origin: [ox!, oy!], size: [w!, h!], layer: r.layer as number, mipCount: r.mipCount as number, sampler: r.sampler as number };
}

/** The TextureBinding at vec4 `offset` of a materials heap. */
export function readTextureBinding(heap: ArrayBuffer, offset: number): TextureBindingRecord {
  const r = readStruct(textureBindingLayout, heapView(heap, offset, textureBindingLayout.size), 0);
  const [a, b, tx] = r.transform0 as number[];
  const [c, d, ty] = r.transform1 as number[];
  return {
    transform0: [a!, b!, tx!],
    transform1: [c!, d!, ty!],
    texture: r.texture as number,
    texCoord: r.texCoord as number,
    scale: r.scale as number,
    flags: r.flags as number,
  };
}

/** texture-sampling.wesl `wrap_texel` (JS % truncates like WGSL's i32 %). */
export function wrapTexel(i: number, size: number, mode: number): number {
  if (mode === SAMPLER_WRAP_CLAMP) return Math.min(Math.max(i, 0), size - 1);
  if (mode === SAMPLER_WRAP_MIRROR) {
    const period = 2 * size;
    const m = ((i % period) + period) % period;
    return m < size ? m : period - 1 - m;
  }
  return ((i % size) + size) % size;
}

function mipSize(info: TextureInfoRecord, level: number): [number, number] {
  return [Math.max(1, info.size[0] >>> level), Math.max(1, info.size[1] >>> level)];
}

function mipOrigin(info: TextureInfoRecord, level: number): [number, number] {
  if (level === 0) return [info.origin[0], info.origin[1]];
  let y = info.origin[1];
  for (let k = 1; k < level; k++) y += Math.max(1, info.size[1] >>> k);
  return [info.origin[0] + info.size[0], y];
}

function loadTexel(atlas: AtlasTexels, info: TextureInfoRecord, origin: [number, number], size: [number, number], x: number, y: number, srgb: boolean): Rgba {
  const px = wrapTexel(x, size[0], (info.sampler >>> SAMPLER_WRAP_S_SHIFT) & 3);
  const py = wrapTexel(y, size[1], (info.sampler >>> SAMPLER_WRAP_T_SHIFT) & 3);
  const layer = atlas.layers[info.layer];
  if (!layer) throw new RangeError(`texture layer ${info.layer} is not in the atlas`);
  const at = ((origin[1] + py) * atlas.layerSize + origin[0] + px) * 4;
  const t: Rgba = [layer[at]! / 255, layer[at + 1]! / 255, layer[at + 2]! / 255, layer[at + 3]! / 255];
  if (srgb) return [srgbToLinear(t[0]), srgbToLinear(t[1]), srgbToLinear(t[2]), t[3]];
  return t;
}

function mix(a: Rgba, b: Rgba, t: number): Rgba {
  return [a[0] * (1 - t) + b[0] * t, a[1] * (1 - t) + b[1] * t, a[2] * (1 - t) + b[2] * t, a[3] * (1 - t) + b[3] * t];
}

/** texture-sampling.wesl `sample_level`: one mip level, nearest or bilinear (texel centres at half-integers). */
export function sampleLevel(atlas: AtlasTexels, info: TextureInfoRecord, u: number, v: number, level: number, linear: boolean, srgb: boolean): Rgba {
  const size = mipSize(info, level);
  const origin = mipOrigin(info, level);
  const s = f32(f32(u) * size[0]);
  const t = f32(f32(v) * size[1]);
  if (!linear) return loadTexel(atlas, info, origin, size, Math.floor(s), Math.floor(t), srgb);
  const ps = f32(s - 0.5);
  const pt = f32(t - 0.5);
  const x0 = Math.floor(ps);
  const y0 = Math.floor(pt);
  const fx = f32(ps - x0);
  const fy = f32(pt - y0);
  const a = loadTexel(atlas, info, origin, size, x0, y0, srgb);
  const b = loadTexel(atlas, info, origin, size, x0 + 1, y0, srgb);
  const c = loadTexel(atlas, info, origin, size, x0, y0 + 1, srgb);
  const d = loadTexel(atlas, info, origin, size, x0 + 1, y0 + 1, srgb);
  return mix(mix(a, b, fx), mix(c, d, fx), fy);
}

/** texture-sampling.wesl `sample_texture_info`: the filtered texture at `uv` and level of detail `lod`. */
export function sampleTextureInfo(atlas: AtlasTexels, info: TextureInfoRecord, uv: readonly [number, number], lod: number, srgb: boolean): Rgba {
  const s = info.sampler;
  const [u, v] = uv;
  const l = f32(lod);
  // Magnification when the footprint is at most a texel (OpenGL 4.6 section 8.14, c = 0).
  if (!(l > 0)) return sampleLevel(atlas, info, u, v, 0, (s & SAMPLER_MAG_LINEAR) !== 0, srgb);
  const minLinear = (s & SAMPLER_MIN_LINEAR) !== 0;
  if ((s & SAMPLER_MIPMAPS) === 0 || info.mipCount <= 1) return sampleLevel(atlas, info, u, v, 0, minLinear, srgb);
  const level = Math.min(l, info.mipCount - 1);
  // OpenGL 4.6 section 8.14.3: the nearest level is ceil(lambda + 1/2) - 1, level 0 up to lambda = 1/2.
  if ((s & SAMPLER_MIP_LINEAR) === 0) return sampleLevel(atlas, info, u, v, Math.max(0, Math.ceil(level - 0.5)), minLinear, srgb);
  const l0 = Math.floor(level);
  const l1 = Math.min(l0 + 1, info.mipCount - 1);
  return mix(sampleLevel(atlas, info, u, v, l0, minLinear, srgb), sampleLevel(atlas, info, u, v, l1, minLinear, srgb), level - l0);
}

/** texture-sampling.wesl `sample_texture`: the texture whose TextureInfo sits at `infoOffset` of the heap. */
export function sampleTexture(atlas: AtlasTexels, heap: ArrayBuffer, infoOffset: number, uv: readonly [number, number], lod: number, srgb: boolean): Rgba {
  return sampleTextureInfo(atlas, readTextureInfo(heap, infoOffset), uv, lod, srgb);
}

/** texture-sampling.wesl `transform_uv`: uv' = [a b tx; c d ty] (uv, 1). */
export function transformUv(b: TextureBindingRecord, uv: readonly [number, number]): [number, number] {
  const [a, bb, tx] = b.transform0;
  const [c, d, ty] = b.transform1;
  return [a * uv[0] + bb * uv[1] + tx, c * uv[0] + d * uv[1] + ty];
}

/**
 * texture-sampling.wesl `texture_lod` (Akenine-Moller et al., "Improved Shader and Texture Level of
 * Detail Using Ray Cones", JCGT 10(1), 2021): log2(width / |cos|) + 0.5 log2(texel area / world area).
 */
export function textureLod(b: TextureBindingRecord, info: TextureInfoRecord, f: TextureFootprint): number {
  if (!(f.worldArea > 0) || !(f.widthOverCos > 0)) return 0;
  const det = Math.abs(b.transform0[0] * b.transform1[1] - b.transform0[1] * b.transform1[0]);
  const uvArea = b.texCoord === 1 ? f.uvArea[1] : f.uvArea[0];
  const texelArea = uvArea * det * info.size[0] * info.size[1];
  if (!(texelArea > 0)) return 0;
  return Math.log2(f.widthOverCos) + 0.5 * Math.log2(texelArea / f.worldArea);
}

/** texture-sampling.wesl `sample_bound_texture`: a material slot's texture at a hit with uv sets uv0, uv1. */
export function sampleBoundTexture(
  atlas: AtlasTexels,
  heap: ArrayBuffer,
  bindingOffset: number,
  uv0: readonly [number, number],
  uv1: readonly [number, number],
  footprint: TextureFootprint,
): Rgba {
  const b = readTextureBinding(heap, bindingOffset);
  const uv = transformUv(b, b.texCoord === 1 ? uv1 : uv0);
  const info = readTextureInfo(heap, b.texture);
  return sampleTextureInfo(atlas, info, uv, textureLod(b, info, footprint), (b.flags & TEXTURE_BINDING_FLAG_SRGB) !== 0);
}
