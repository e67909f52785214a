/**
 * The U-Net of Open Image Denoise's `RT` filter as a list of 3x3 convolutions, read from a weights
 * file (OIDN core/unet_filter.cpp addUNet / addUNetLarge; training/model.py). Every convolution is
 * followed by a ReLU (OIDN applies one to the last layer too); 2x2 max pooling follows the encoder
 * convolutions that end a level; the decoder's first convolution of a level reads the nearest-
 * neighbour 2x upsampled output of the level below concatenated (channels after it) with the
 * encoder's skip tensor (the network input at full resolution). Images are padded to multiples of
 * 16 (four poolings). The channel counts come from the weights, so the base, small and large
 * variants all load; the input channels say which inputs the model takes: 3 colour, 6 colour +
 * albedo, 9 colour + albedo + normal.
 */
import { GpuRendererError } from '../../../errors/gpu-renderer-error.ts';
import type { TzaTensor } from './tza.ts';

/** One convolution: which tensors it reads and what it writes. */
export interface UNetConv {
  name: string;
  /** Source tensor names: `input` or another convolution's name; the first is upsampled when `upsample`. */
  sources: [string] | [string, string];
  upsample: boolean;
  pool: boolean;
  /** Resolution level the convolution runs at (0: full, k: 1/2^k). */
  level: number;
  /** Input channels of each source (the weights' input channels, split at the concatenation). */
  sourceChannels: number[];
  outChannels: number;
  /** oihw float weights and the bias. */
  weights: Float32Array;
  bias: Float32Array;
}

export interface UNetModel {
  /** 'base' (and small: the same graph, narrower), or 'large'. */
  variant: 'base' | 'large';
  /** 3 (colour), 6 (+ albedo) or 9 (+ albedo + normal). */
  inputChannels: number;
  convs: UNetConv[];
}

/** Spatial alignment the network needs (four 2x2 poolings). */
export const unetAlignment = 16;
/** Receptive field in pixels (OIDN receptiveFieldBase / receptiveFieldLarge): tiles overlap by half of it, rounded up to 16. */
export const unetReceptiveField = { base: 174, large: 202 } as const;

type Step = { name: string; from: string; skip?: string; pool?: boolean; up?: boolean };

const baseGraph: Step[] = [
  { name: 'enc_conv0', from: 'input' },
  { name: 'enc_conv1', from: 'enc_conv0', pool: true },
  { name: 'enc_conv2', from: 'enc_conv1', pool: true },
  { name: 'enc_conv3', from: 'enc_conv2', pool: true },
  { name: 'enc_conv4', from: 'enc_conv3', pool: true },
  { name: 'enc_conv5a', from: 'enc_conv4' },
  { name: 'enc_conv5b', from: 'enc_conv5a' },
  { name: 'dec_conv4a', from: 'enc_conv5b', up: true, skip: 'enc_conv3' },
  { name: 'dec_conv4b', from: 'dec_conv4a' },
  { name: 'dec_conv3a', from: 'dec_conv4b', up: true, skip: 'enc_conv2' },
  { name: 'dec_conv3b', from: 'dec_conv3a' },
  { name: 'dec_conv2a', from: 'dec_conv3b', up: true, skip: 'enc_conv1' },
  { name: 'dec_conv2b', from: 'dec_conv2a' },
  { name: 'dec_conv1a', from: 'dec_conv2b', up: true, skip: 'input' },
  { name: 'dec_conv1b', from: 'dec_conv1a' },
  { name: 'dec_conv0', from: 'dec_conv1b' },
];

const largeGraph: Step[] = [
  { name: 'enc_conv1a', from: 'input' },
  { name: 'enc_conv1b', from: 'enc_conv1a', pool: true },
  { name: 'enc_conv2a', from: 'enc_conv1b' },
  { name: 'enc_conv2b', from: 'enc_conv2a', pool: true },
  { name: 'enc_conv3a', from: 'enc_conv2b' },
  { name: 'enc_conv3b', from: 'enc_conv3a', pool: true },
  { name: 'enc_conv4a', from: 'enc_conv3b' },
  { name: 'enc_conv4b', from: 'enc_conv4a', pool: true },
  { name: 'enc_conv5a', from: 'enc_conv4b' },
  { name: 'enc_conv5b', from: 'enc_conv5a' },
  { name: 'dec_conv4a', from: 'enc_conv5b', up: true, skip: 'enc_conv3b' },
  { name: 'dec_conv4b', from: 'dec_conv4a' },
  { name: 'dec_conv3a', from: 'dec_conv4b', up: true, skip: 'enc_conv2b' },
  { name: 'dec_conv3b', from: 'dec_conv3a' },
  { name: 'dec_conv2a', from: 'dec_conv3b', up: true, skip: 'enc_conv1b' },
  { name: 'dec_conv2b', from: 'dec_conv2a' },
  { name: 'dec_conv1a', from: 'dec_conv2b', up: true, skip: 'input' },
  { name: 'dec_conv1b', from: 'dec_conv1a' },
  { name: 'dec_conv1c', from: 'dec_conv1b' },
];

function invalid(field: string, message: string): never {
  throw new GpuRendererError('INVALID_OPTION', `unsupported OIDN weights: ${message}`, { field });
}

/** Builds the network from parsed weights; `field` names the weights in errors. */
export function unetFromTensors(tensors: ReadonlyMap<string, TzaTensor>, field = 'weights'): UNetModel {
  const variant = tensors.has('enc_conv1b.weight') ? 'large' : 'base';
  const graph = variant === 'large' ? largeGraph : baseGraph;
  const channels = new Map<string, number>();
  const levels = new Map<string, number>([['input', 0]]);
  const convs: UNetConv[] = [];
  for (const step of graph) {
    const w = tensors.get(`${step.name}.weight`);
    const b = tensors.get(`${step.name}.bias`);
    if (!w || !b) invalid(field, `tensor ${step.name}.weight or .bias is missing`);
    if (w.layout !== 'oihw' || w.dims.length !== 4 || w.dims[2] !== 3 || w.dims[3] !== 3) invalid(field, `${step.name}.weight is not a 3x3 oihw kernel`);
    const [outChannels, inChannels] = w.dims as [number, number];
    if (b.dims.length !== 1 || b.dims[0] !== outChannels) invalid(field, `${step.name}.bias has ${b.dims.join('x')} values, expected ${outChannels}`);
    if (step.from === 'input') channels.set('input', inChannels);
    const fromChannels = channels.get(step.from)!;
    const sourceChannels = step.skip ? [fromChannels, channels.get(step.skip)!] : [fromChannels];
    const total = sourceChannels.reduce((a, c) => a + c, 0);
    if (total !== inChannels) invalid(field, `${step.name} takes ${inChannels} channels, but its sources give ${total}`);
    const level = step.up ? levels.get(step.from)! - 1 : levels.get(step.from)!;
    if (step.skip && levels.get(step.skip) !== level) invalid(field, `${step.name}: the skip connection ${step.skip} is at another resolution`);
    channels.set(step.name, outChannels);
    levels.set(step.name, level + (step.pool ? 1 : 0));
    convs.push({
      name: step.name,
      sources: step.skip ? [step.from, step.skip] : [step.from],
      upsample: step.up === true,
      pool: step.pool === true,
      level,
      sourceChannels,
      outChannels,
      weights: w.data,
      bias: b.data,
    });
  }
  const inputChannels = channels.get('input')!;
  if (inputChannels !== 3 && inputChannels !== 6 && inputChannels !== 9) invalid(field, `the network takes ${inputChannels} input channels (expected 3, 6 or 9)`);
  const last = convs[convs.length - 1]!;
  if (last.outChannels !== 3) invalid(field, `the network outputs ${last.outChannels} channels (expected 3: an RGB filter)`);
  return { variant, inputChannels, convs };
}
