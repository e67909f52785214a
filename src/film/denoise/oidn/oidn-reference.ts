/**
 * CPU evaluation of Open Image Denoise's `RT` network (unet.ts) on a whole image, written for
 * clarity: plain loops over channel-major float64 tensors, the same input and output processing as
 * OIDN (transfer.ts). It is the independent implementation the WebGPU network (oidn-network.ts) is
 * tested against, and usable offline on small images (it takes about a second per 64x64 pixels).
 */
import { GpuRendererError } from '../../../errors/gpu-renderer-error.ts';
import { requireLinearRgbaImage, type LinearRgbaImage } from '../../../io/images/linear-image.ts';
import { autoexposure, puForward, puInverse, puNormScale, sanitize } from './transfer.ts';
import { unetAlignment, type UNetModel } from './unet.ts';

export interface OidnReferenceInput {
  /** Linear HDR radiance (RGBA, alpha ignored). */
  color: LinearRgbaImage;
  /** First-hit albedo in [0, 1] (models with 6 or 9 input channels). */
  albedo?: LinearRgbaImage;
  /** First-hit shading normal, any length, in [-1, 1] (models with 9 input channels). */
  normal?: LinearRgbaImage;
  /** Exact emission taken out of the colour before the network and added back after (optional). */
  emission?: LinearRgbaImage;
  /** Multiplies the colour before the transfer function; default: OIDN's autoexposure. */
  inputScale?: number;
}

/** A channel-major tensor: data[(c * height + y) * width + x]. */
interface Tensor {
  channels: number;
  width: number;
  height: number;
  data: Float64Array;
}

const tensor = (channels: number, width: number, height: number): Tensor => ({ channels, width, height, data: new Float64Array(channels * width * height) });

/** 3x3 convolution with zero padding over the concatenated sources, bias, ReLU. */
function conv3x3(sources: Tensor[], weights: Float32Array, bias: Float32Array, outChannels: number): Tensor {
  const { width: w, height: h } = sources[0]!;
  const out = tensor(outChannels, w, h);
  const inChannels = sources.reduce((a, s) => a + s.channels, 0);
  for (let o = 0; o < outChannels; o++) {
    const plane = out.data.subarray(o * w * h, (o + 1) * w * h);
    plane.fill(bias[o]!);
    let i = 0;
    for (const source of sources) {
      for (let c = 0; c < source.channels; c++, i++) {
        const input = source.data.subarray(c * w * h, (c + 1) * w * h);
        for (let ky = 0; ky < 3; ky++) {
          for (let kx = 0; kx < 3; kx++) {
            const k = weights[((o * inChannels + i) * 3 + ky) * 3 + kx]!;
            const dy = ky - 1, dx = kx - 1;
            for (let y = Math.max(0, -dy); y < Math.min(h, h - dy); y++) {
              const row = y * w, inRow = (y + dy) * w + dx;
              for (let x = Math.max(0, -dx); x < Math.min(w, w - dx); x++) plane[row + x]! += k * input[inRow + x]!;
            }
          }
        }
      }
    }
    for (let p = 0; p < plane.length; p++) if (!(plane[p]! > 0)) plane[p] = 0;
  }
  return out;
}

function maxPool2x2(t: Tensor): Tensor {
  const w = t.width / 2, h = t.height / 2;
  const out = tensor(t.channels, w, h);
  for (let c = 0; c < t.channels; c++) {
    for (let y = 0; y < h; y++) {
      for (let x = 0; x < w; x++) {
        const at = (c * t.height + 2 * y) * t.width + 2 * x;
        out.data[(c * h + y) * w + x] = Math.max(t.data[at]!, t.data[at + 1]!, t.data[at + t.width]!, t.data[at + t.width + 1]!);
      }
    }
  }
  return out;
}

function upsample2x(t: Tensor): Tensor {
  const w = t.width * 2, h = t.height * 2;
  const out = tensor(t.channels, w, h);
  for (let c = 0; c < t.channels; c++) {
    for (let y = 0; y < h; y++) {
      for (let x = 0; x < w; x++) out.data[(c * h + y) * w + x] = t.data[(c * t.height + (y >> 1)) * t.width + (x >> 1)]!;
    }
  }
  return out;
}

/** Runs the network on the image; returns RGBA (alpha 1), top row first. */
export function denoiseOidnReference(model: UNetModel, input: OidnReferenceInput): Float32Array {
  const pixels = requireLinearRgbaImage(input.color, 'color');
  const { width, height } = input.color;
  const aux: { key: 'albedo' | 'normal'; needed: boolean }[] = [
    { key: 'albedo', needed: model.inputChannels >= 6 },
    { key: 'normal', needed: model.inputChannels >= 9 },
  ];
  for (const { key, needed } of aux) {
    const image = input[key];
    if (needed !== (image !== undefined)) throw new GpuRendererError('INVALID_OPTION', needed ? `the ${model.inputChannels}-channel model needs ${key}` : `the ${model.inputChannels}-channel model takes no ${key}`, { field: key });
    if (image) {
      requireLinearRgbaImage(image, key);
      if (image.width !== width || image.height !== height) throw new GpuRendererError('INVALID_OPTION', `expected ${width}x${height} like color`, { field: key });
    }
  }
  let color = input.color.data;
  if (input.emission) {
    requireLinearRgbaImage(input.emission, 'emission');
    if (input.emission.width !== width || input.emission.height !== height) throw new GpuRendererError('INVALID_OPTION', `expected ${width}x${height} like color`, { field: 'emission' });
    const e = input.emission.data;
    color = color.map((v, i) => (i % 4 === 3 ? v : sanitize(v) - sanitize(e[i]!)));
  }
  const scale = input.inputScale ?? autoexposure(color, width, height);
  const pw = Math.ceil(width / unetAlignment) * unetAlignment;
  const ph = Math.ceil(height / unetAlignment) * unetAlignment;
  // Input processing (OIDN input_process): scaled colour through the normalised PU curve, albedo
  // clamped to [0, 1], normal clamped to [-1, 1] and mapped to [0, 1]; zeros in the padding.
  const x0 = tensor(model.inputChannels, pw, ph);
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      const p = y * width + x;
      const at = (c: number) => (c * ph + y) * pw + x;
      for (let c = 0; c < 3; c++) {
        x0.data[at(c)] = puForward(sanitize(color[4 * p + c]! * scale)) * puNormScale;
        if (input.albedo) x0.data[at(3 + c)] = sanitize(input.albedo.data[4 * p + c]!, 1);
        if (input.normal) x0.data[at(6 + c)] = Math.min(Math.max(Number.isNaN(input.normal.data[4 * p + c]!) ? 0 : input.normal.data[4 * p + c]!, -1), 1) * 0.5 + 0.5;
      }
    }
  }
  const tensors = new Map<string, Tensor>([['input', x0]]);
  let last: Tensor = x0;
  for (const conv of model.convs) {
    const sources = conv.sources.map((name, i) => {
      const t = tensors.get(name)!;
      return i === 0 && conv.upsample ? upsample2x(t) : t;
    });
    let out = conv3x3(sources, conv.weights, conv.bias, conv.outChannels);
    if (conv.pool) out = maxPool2x2(out);
    tensors.set(conv.name, out);
    last = out;
  }
  // Output processing (OIDN output_process): PU inverse of the (non-negative) network output, / scale.
  const outputScale = scale !== 0 ? 1 / scale : 0;
  const result = new Float32Array(pixels * 4);
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      const p = y * width + x;
      for (let c = 0; c < 3; c++) {
        result[4 * p + c] = puInverse(sanitize(last.data[(c * ph + y) * pw + x]!) / puNormScale) * outputScale + (input.emission ? sanitize(input.emission.data[4 * p + c]!) : 0);
      }
      result[4 * p + 3] = 1;
    }
  }
  return result;
}
