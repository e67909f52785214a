/**
 * GPU layouts of the OIDN network (conv.wesl): tensors of vec4 channel groups, and each
 * convolution's weights as 16-output-channel blocks of 4x4 matrices. Pure functions, shared by the
 * WebGPU network and its tests.
 */
import type { UNetConv, UNetModel } from './unet.ts';

export type OidnPrecision = 'f16' | 'f32';

/** Output channels one workgroup computes (conv.wesl: 4 vec4 groups). */
export const convBlockChannels = 16;

export const channelGroups = (channels: number): number => Math.ceil(channels / 4);

/** Where each of a convolution's input channels lands in its padded, concatenated input. */
export function paddedInputChannel(conv: UNetConv, channel: number): number {
  const first = conv.sourceChannels[0]!;
  return channel < first ? channel : 4 * channelGroups(first) + (channel - first);
}

export interface PackedConv {
  /** vec4 channel groups of each source. */
  sourceGroups: [number, number];
  blocks: number;
  destinationGroups: number;
  /** Bias vec4s (blocks x 4), then the matrices; as float32 values (4 per vec4). */
  values: Float32Array;
}

/**
 * Packs one convolution: blocks x 4 bias vec4s, then for block b, input group g, tap t (ky * 3 +
 * kx) and output group j a 4x4 matrix stored as 4 column vec4s, column i = the weights of input
 * channel 4g + i for output channels 16b + 4j .. + 3. Padding channels are zero.
 */
export function packConv(conv: UNetConv): PackedConv {
  const groupsA = channelGroups(conv.sourceChannels[0]!);
  const groupsB = conv.sourceChannels[1] === undefined ? 0 : channelGroups(conv.sourceChannels[1]);
  const inputs = groupsA + groupsB;
  const blocks = Math.ceil(conv.outChannels / convBlockChannels);
  const biasValues = blocks * convBlockChannels;
  const values = new Float32Array(biasValues + blocks * inputs * 9 * 4 * 16);
  values.set(conv.bias);
  const inChannels = conv.sourceChannels.reduce((a, c) => a + c, 0);
  for (let o = 0; o < conv.outChannels; o++) {
    const block = Math.floor(o / convBlockChannels);
    const j = Math.floor((o % convBlockChannels) / 4);
    const lane = o % 4;
    for (let i = 0; i < inChannels; i++) {
      const padded = paddedInputChannel(conv, i);
      const group = padded >> 2;
      const column = padded & 3;
      for (let tap = 0; tap < 9; tap++) {
        const matrix = ((block * inputs + group) * 9 + tap) * 4 + j;
        values[biasValues + matrix * 16 + column * 4 + lane] = conv.weights[(o * inChannels + i) * 9 + tap]!;
      }
    }
  }
  return { sourceGroups: [groupsA, groupsB], blocks, destinationGroups: channelGroups(conv.outChannels), values };
}

/** IEEE 754 binary16 bits of a number, rounded to nearest even (overflow to infinity). */
export function floatToHalfBits(value: number): number {
  const f32 = new Float32Array(1);
  const u32 = new Uint32Array(f32.buffer);
  f32[0] = value;
  const x = u32[0]!;
  const sign = (x >>> 16) & 0x8000;
  const exponent = (x >>> 23) & 0xff;
  let mantissa = x & 0x7fffff;
  if (exponent === 0xff) return sign | 0x7c00 | (mantissa ? 0x200 : 0);
  const e = exponent - 127 + 15;
  if (e >= 31) return sign | 0x7c00;
  if (e <= 0) {
    if (e < -10) return sign;
    mantissa |= 0x800000;
    const shift = 14 - e;
    const half = mantissa >>> shift;
    const rest = mantissa & ((1 << shift) - 1);
    const midpoint = 1 << (shift - 1);
    return sign | (half + (rest > midpoint || (rest === midpoint && (half & 1)) ? 1 : 0));
  }
  let half = (e << 10) | (mantissa >>> 13);
  const rest = mantissa & 0x1fff;
  if (rest > 0x1000 || (rest === 0x1000 && (half & 1))) half++;
  return sign | half;
}

/** The bytes of float values in the given precision (vec4<f16> is 8 bytes, vec4<f32> 16). */
export function encodeValues(values: Float32Array, precision: OidnPrecision): ArrayBuffer {
  if (precision === 'f32') return values.slice().buffer;
  const halves = new Uint16Array(values.length);
  for (let i = 0; i < values.length; i++) halves[i] = floatToHalfBits(values[i]!);
  return halves.buffer;
}

export const bytesPerGroup = (precision: OidnPrecision): number => (precision === 'f16' ? 8 : 16);

/** A tensor of the network for a tile: its channel groups and resolution level. */
export interface PlannedTensor {
  name: string;
  groups: number;
  level: number;
  /** Index of the step that writes it (-1: the input pass) and of the last step that reads it. */
  producedAt: number;
  lastReadAt: number;
  /** The buffer it lives in. */
  slot: number;
}

export interface TensorPlan {
  tensors: Map<string, PlannedTensor>;
  /** Byte size of every buffer. */
  slotBytes: number[];
  totalBytes: number;
}

/**
 * Assigns the network's tensors for a `width` x `height` tile (multiples of 16) to as few buffers
 * as their lifetimes allow: a buffer is reused once its tensor's last reader has run (a step never
 * writes a buffer it reads), best fit first, a buffer growing to its largest tenant.
 */
export function planTensors(model: UNetModel, width: number, height: number, precision: OidnPrecision): TensorPlan {
  const tensors = new Map<string, PlannedTensor>();
  const order: PlannedTensor[] = [];
  const add = (name: string, groups: number, level: number, producedAt: number) => {
    const t = { name, groups, level, producedAt, lastReadAt: producedAt, slot: -1 };
    tensors.set(name, t);
    order.push(t);
  };
  add('input', channelGroups(model.inputChannels), 0, -1);
  model.convs.forEach((conv, i) => {
    for (const source of conv.sources) tensors.get(source)!.lastReadAt = i;
    add(conv.name, channelGroups(conv.outChannels), conv.level + (conv.pool ? 1 : 0), i);
  });
  // The output pass reads the last tensor after every convolution.
  order[order.length - 1]!.lastReadAt = model.convs.length;
  const bytes = (t: PlannedTensor) => t.groups * (width >> t.level) * (height >> t.level) * bytesPerGroup(precision);
  const slotBytes: number[] = [];
  const holder: (PlannedTensor | null)[] = [];
  for (const t of order) {
    const need = bytes(t);
    let best = -1;
    for (let s = 0; s < slotBytes.length; s++) {
      const h = holder[s];
      if (h && h.lastReadAt >= t.producedAt) continue;
      // Prefer the smallest buffer that fits, else the largest one (which then grows).
      if (best < 0) best = s;
      else {
        const fits = slotBytes[s]! >= need, bestFits = slotBytes[best]! >= need;
        if ((fits && (!bestFits || slotBytes[s]! < slotBytes[best]!)) || (!fits && !bestFits && slotBytes[s]! > slotBytes[best]!)) best = s;
      }
    }
    if (best < 0) {
      best = slotBytes.length;
      slotBytes.push(0);
      holder.push(null);
    }
    slotBytes[best] = Math.max(slotBytes[best]!, need);
    holder[best] = t;
    t.slot = best;
  }
  return { tensors, slotBytes, totalBytes: slotBytes.reduce((a, b) => a + b, 0) };
}

export interface OidnTile {
  /** Image pixel of the tile tensor's (0, 0). */
  origin: [number, number];
  /** The image pixels it writes: [min, max). */
  writeMin: [number, number];
  writeMax: [number, number];
}

export interface TilePlan {
  /** Tile tensor size (multiples of 16). */
  tileWidth: number;
  tileHeight: number;
  overlap: number;
  tiles: OidnTile[];
}

const roundUp = (n: number, k: number): number => Math.ceil(n / k) * k;

/**
 * Splits one axis of `size` pixels for tiles of `tile` pixels (one tile, padded to 16, when it
 * covers the axis). Tile origins stay on the 16-pixel grid of the whole image, so every tile pools
 * the same windows the untiled network would, and no tile reaches past the image padded to 16: the
 * network's zero padding sits where the untiled network has it (OIDN aligns its last tile the same
 * way), so tiled and untiled results agree.
 */
function axis(size: number, tile: number, overlap: number): { tile: number; spans: { origin: number; begin: number; end: number }[] } {
  const padded = roundUp(size, 16);
  if (padded <= tile) return { tile: padded, spans: [{ origin: 0, begin: 0, end: size }] };
  // Snapping an origin down to the grid costs up to 15 pixels of the inner part.
  const inner = tile - 2 * overlap - 16;
  const count = Math.ceil(size / inner);
  const spans = [];
  for (let i = 0; i < count; i++) {
    const begin = Math.floor((i * size) / count);
    const end = Math.floor(((i + 1) * size) / count);
    spans.push({ origin: Math.max(0, Math.min(Math.floor((begin - overlap) / 16) * 16, padded - tile)), begin, end });
  }
  return { tile, spans };
}

/**
 * Tiles for a `width` x `height` image (OIDN UNetFilter::init): one tile when the padded image
 * fits `fits(tileWidth, tileHeight)`; else the largest square tile (a multiple of 16 with an inner
 * part of 16 pixels at least) that fits, tiles overlapping by `overlap` pixels on every inner side
 * so each written pixel saw the context its receptive field needs. All tiles have one size, so they
 * share one set of buffers.
 */
export function planTiles(width: number, height: number, overlap: number, fits: (tileWidth: number, tileHeight: number) => boolean): TilePlan {
  let tile = Math.max(roundUp(width, 16), roundUp(height, 16));
  if (!fits(Math.min(tile, roundUp(width, 16)), Math.min(tile, roundUp(height, 16)))) {
    const smallest = 2 * overlap + 32;
    tile = roundUp(Math.min(tile, 8192), 16);
    while (tile > smallest && !fits(Math.min(tile, roundUp(width, 16)), Math.min(tile, roundUp(height, 16)))) tile -= 16;
    if (tile <= smallest) tile = smallest;
  }
  const x = axis(width, tile, overlap);
  const y = axis(height, tile, overlap);
  const tiles: OidnTile[] = [];
  for (const sy of y.spans) {
    for (const sx of x.spans) tiles.push({ origin: [sx.origin, sy.origin], writeMin: [sx.begin, sy.begin], writeMax: [sx.end, sy.end] });
  }
  return { tileWidth: x.tile, tileHeight: y.tile, overlap, tiles };
}
