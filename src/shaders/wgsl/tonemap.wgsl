// Display transforms: scene-referred linear radiance -> display-referred linear [0, 1] -> sRGB.
// Mirrored bit-for-bit in intent by src/post/tone-mapping.ts (tests compare the two).

const TONE_MAPPING_NEUTRAL: u32 = 0u;
const TONE_MAPPING_ACES: u32 = 1u;
const TONE_MAPPING_LINEAR: u32 = 2u;

// Khronos PBR Neutral tone mapper, the reference implementation from
// https://github.com/KhronosGroup/ToneMapping/blob/main/PBR_Neutral/pbrNeutral.glsl
// Below the compression start, colours only receive the small toe offset (hue and the differences
// between channels are preserved exactly); above it the peak is compressed towards 1 and the
// colour desaturated towards white.
fn tonemap_pbr_neutral(c: vec3f) -> vec3f {
  let start_compression = 0.8 - 0.04;
  let desaturation = 0.15;

  var color = c;
  let x = min(color.r, min(color.g, color.b));
  let offset = select(0.04, x - 6.25 * x * x, x < 0.08);
  color -= vec3f(offset);

  let peak = max(color.r, max(color.g, color.b));
  if (peak < start_compression) {
    return color;
  }

  let d = 1.0 - start_compression;
  let new_peak = 1.0 - d * d / (peak + d - start_compression);
  color *= new_peak / peak;

  let g = 1.0 - 1.0 / (desaturation * (peak - new_peak) + 1.0);
  return mix(color, vec3f(new_peak), g);
}

// Stephen Hill's fit of the ACES RRT + sRGB ODT (BakingLab, ACES.hlsl:
// https://github.com/TheRealMJP/BakingLab/blob/master/BakingLab/ACES.hlsl), the same curve and
// matrices that three.js's ACESFilmicToneMapping uses. Input and output are linear sRGB (Rec. 709
// primaries, D65). Unlike three.js, no extra 1/0.6 exposure boost is applied: three.js's result
// equals this one with exposure multiplied by 1/0.6.
fn aces_rrt_odt_fit(v: vec3f) -> vec3f {
  let a = v * (v + 0.0245786) - 0.000090537;
  let b = v * (0.983729 * v + 0.4329510) + 0.238081;
  return a / b;
}

fn tonemap_aces(c: vec3f) -> vec3f {
  // sRGB -> XYZ -> D65-to-D60 -> AP1 -> RRT_SAT (columns; WGSL matrices are column-major).
  let aces_input = mat3x3f(
    vec3f(0.59719, 0.07600, 0.02840),
    vec3f(0.35458, 0.90834, 0.13383),
    vec3f(0.04823, 0.01566, 0.83777));
  // ODT_SAT -> XYZ -> D60-to-D65 -> sRGB.
  let aces_output = mat3x3f(
    vec3f(1.60475, -0.10208, -0.00327),
    vec3f(-0.53108, 1.10813, -0.07276),
    vec3f(-0.07367, -0.00605, 1.07602));
  let fitted = aces_rrt_odt_fit(aces_input * c);
  return clamp(aces_output * fitted, vec3f(0.0), vec3f(1.0));
}

// The exact sRGB transfer function of IEC 61966-2-1:1999 (piecewise linear toe + 2.4 power),
// not the 2.2 gamma approximation.
fn linear_to_srgb(c: vec3f) -> vec3f {
  let lo = c * 12.92;
  let hi = 1.055 * pow(max(c, vec3f(0.0031308)), vec3f(1.0 / 2.4)) - 0.055;
  return select(hi, lo, c <= vec3f(0.0031308));
}

// Display-referred linear RGB in [0, 1]. Exposure is applied by the caller before this.
fn apply_tone_mapping(c: vec3f, mode: u32) -> vec3f {
  // Radiance is non-negative; a negative input would be an upstream bug, not something to map.
  let x = max(c, vec3f(0.0));
  var mapped: vec3f;
  switch mode {
    case TONE_MAPPING_ACES: {
      mapped = tonemap_aces(x);
    }
    case TONE_MAPPING_LINEAR: {
      // Clamped only because a display cannot show more; the radiance itself is never clamped.
      mapped = x;
    }
    default: {
      mapped = tonemap_pbr_neutral(x);
    }
  }
  return clamp(mapped, vec3f(0.0), vec3f(1.0));
}
