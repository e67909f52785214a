import type { BindingSpec } from '../../../gpu-layout/bindings.ts';

/**
 * Bindings of the OIDN network's programs (conv.wesl, image.wesl), one group: each dispatch binds
 * the few it uses. Tensors are channel-major arrays of vec4 channel groups, `Tensor4` (vec4 of f16
 * where the device has shader-f16, else of f32: precision.wesl).
 */
export const oidnBindings = {
  oidnConv: { group: 0, binding: 0, kind: 'uniform', type: 'OidnConvUniforms', doc: 'the convolution: sizes, sources, pooling' },
  oidnSourceA: { group: 0, binding: 1, kind: 'storage', access: 'read', type: 'array<Tensor4>', doc: 'first source tensor (or the network output, for the output pass)' },
  oidnSourceB: { group: 0, binding: 2, kind: 'storage', access: 'read', type: 'array<Tensor4>', doc: 'second source tensor, concatenated after the first' },
  oidnWeights: { group: 0, binding: 3, kind: 'storage', access: 'read', type: 'array<Tensor4>', doc: 'the bias vec4s, then 4x4 weight matrices (columns: input channels)' },
  oidnDestination: { group: 0, binding: 4, kind: 'storage', access: 'read_write', type: 'array<Tensor4>', doc: 'destination tensor' },
  oidnImage: { group: 0, binding: 5, kind: 'uniform', type: 'OidnImageUniforms', doc: 'image, tile and input layout' },
  oidnColor: { group: 0, binding: 6, kind: 'storage', access: 'read', type: 'array<vec4f>', doc: 'linear HDR colour (or a film: radiance sums and the sample count)' },
  oidnAlbedo: { group: 0, binding: 7, kind: 'storage', access: 'read', type: 'array<vec4f>', doc: 'albedo (or the film AOV sums)' },
  oidnNormal: { group: 0, binding: 8, kind: 'storage', access: 'read', type: 'array<vec4f>', doc: 'shading normal (or the film AOV sums)' },
  oidnScale: { group: 0, binding: 9, kind: 'storage', access: 'read_write', type: 'array<f32>', doc: '[0]: the input scale (autoexposure or given)' },
  oidnExposureBins: { group: 0, binding: 10, kind: 'storage', access: 'read_write', type: 'array<f32>', doc: 'mean luminance of every autoexposure bin' },
  oidnOutput: { group: 0, binding: 11, kind: 'storage', access: 'read_write', type: 'array<vec4f>', doc: 'the denoised image (rgb, 1)' },
  oidnEmission: { group: 0, binding: 12, kind: 'storage', access: 'read', type: 'array<vec4f>', doc: 'exact emission taken out before the network and added back after (or the film AOV sums)' },
} as const satisfies Record<string, BindingSpec>;

export type OidnBindingName = keyof typeof oidnBindings;
