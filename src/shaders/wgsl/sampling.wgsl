// Per-pixel low-discrepancy samples: Owen-scrambled Sobol (0,2)-sequence pairs, padded across
// dimensions by independent index shuffles. Burley, "Practical Hash-based Owen Scrambling",
// JCGT 9(4), 2020. Deterministic in (seed, pixel, sample index, dimension).

fn hash_u32(x_in: u32) -> u32 {
  // lowbias32 (Chris Wellons' hash prospector).
  var x = x_in;
  x ^= x >> 16u;
  x *= 0x7feb352du;
  x ^= x >> 15u;
  x *= 0x846ca68bu;
  x ^= x >> 16u;
  return x;
}

fn hash_combine(seed: u32, v: u32) -> u32 {
  return seed ^ (v + 0x9e3779b9u + (seed << 6u) + (seed >> 2u));
}

fn laine_karras_permutation(x_in: u32, seed: u32) -> u32 {
  var x = x_in + seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return x;
}

fn nested_uniform_scramble(x: u32, seed: u32) -> u32 {
  return reverseBits(laine_karras_permutation(reverseBits(x), seed));
}

fn sobol_dimension0(index: u32) -> u32 {
  return reverseBits(index);
}

// Second Sobol dimension (primitive polynomial x + 1): direction numbers v_k = v_{k-1} ^ (v_{k-1} >> 1).
fn sobol_dimension1(index: u32) -> u32 {
  var result = 0u;
  var v = 0x80000000u;
  var i = index;
  loop {
    if (i == 0u) { break; }
    if ((i & 1u) != 0u) { result ^= v; }
    i = i >> 1u;
    v ^= v >> 1u;
  }
  return result;
}

fn u32_to_unit_float(x: u32) -> f32 {
  // 24 high bits: exactly representable and strictly below 1.
  return f32(x >> 8u) * (1.0 / 16777216.0);
}

// Seed of one pixel's sequence.
fn pixel_sequence_seed(seed: u32, pixel_index: u32) -> u32 {
  return hash_u32(hash_combine(hash_u32(seed), pixel_index));
}

// The 2-D sample `dimension` of sample `index` in the sequence with seed `pixel_seed`.
fn sample_2d(pixel_seed: u32, index: u32, dimension: u32) -> vec2f {
  let seed = hash_u32(hash_combine(pixel_seed, dimension));
  let shuffled = nested_uniform_scramble(index, seed);
  let x = nested_uniform_scramble(sobol_dimension0(shuffled), hash_combine(seed, 0x5851f42du));
  let y = nested_uniform_scramble(sobol_dimension1(shuffled), hash_combine(seed, 0x14057b7eu));
  return vec2f(u32_to_unit_float(x), u32_to_unit_float(y));
}

// Dimension pairs used by one path sample. Bounce d uses SAMPLE_PAIRS_PER_BOUNCE pairs from
// 1 + d * SAMPLE_PAIRS_PER_BOUNCE on.
const SAMPLE_PAIR_CAMERA: u32 = 0u;
const SAMPLE_PAIRS_PER_BOUNCE: u32 = 4u;
const SAMPLE_PAIR_BSDF_DIRECTION: u32 = 0u;
const SAMPLE_PAIR_LIGHT_POSITION: u32 = 1u;
const SAMPLE_PAIR_LIGHT_AND_LOBE: u32 = 2u;
const SAMPLE_PAIR_ROULETTE: u32 = 3u;

fn bounce_dimension(depth: u32, pair: u32) -> u32 {
  return 1u + depth * SAMPLE_PAIRS_PER_BOUNCE + pair;
}
