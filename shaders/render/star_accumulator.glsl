// The stars' light of a band before it joins the band's output
// (render/night/star_pass.h): per band pixel and channel (r, g, b) a 64-bit
// two's-complement integer of the linear sRGB radiance × exposure in fixed
// point, STAR_COUNTS_PER_UNIT counts per unit: a constant, the same on every
// node, band and frame, so two outputs that hold the same star at the same
// pixel position add the same counts for it whatever other stars their bands
// hold (a step chosen per band made the quadrants of a dome master quantize a
// star differently from the whole: a seam within one code).
//
// Integer atomics make the sum of overlapping stars independent of the order
// the GPU runs them in (float atomics are neither core GL 4.5 nor
// associative): every node, Mesa and NVIDIA add the same numbers. Core GL 4.5
// has 32-bit atomics only, so each value is two uints, low and high word, and
// a star adds its low word with atomicAdd, whose return value (the old low
// word) tells whether the addition wrapped past 2³²: then one more is carried
// into the high word. Each addition detects its own wrap, so the 64-bit sum is
// exact in any order; a star adds to the high word only when it carries or is
// negative or brighter than 2³² counts (16 units), so a star costs the same
// three atomics per pixel as the 32-bit accumulator did.
//
// Range (docs/night-sky.md, "Rendering the night sky"): the step 2⁻²⁸ ≈ 3.7e-9
// of exposed radiance is 40 000 counts at half an 8-bit code at black (1.5e-4);
// a star's exposed radiance is clamped to ±STAR_RADIANCE_LIMIT = 65 504 (the
// largest half float, 10⁴ past the tone curve's white) before it is added, so
// a pixel holds up to 2⁶³ / (65 504 · 2²⁸) ≈ 5.2 · 10⁵ such stars without
// overflow: more than any catalogue this renderer loads has in one pixel.
//
// Layout: per pixel eight uints, (r_lo, r_hi, g_lo, g_hi) (b_lo, b_hi, 0, 0):
// star_splat.comp adds to single uints (atomics); night_sky.comp reads and
// clears a pixel's eight as two 16-byte accesses (llvmpipe runs each storage
// access as a loop over the SIMD lanes), defining STAR_PIXELS. The buffer is
// all zeros between passes.
#define STAR_COUNTS_PER_UNIT 268435456.0  // 2^28
#define STAR_UNIT_PER_COUNT 3.7252902984619140625e-9  // 2^-28
#define STAR_RADIANCE_LIMIT 65504.0
#define STAR_UINTS_PER_PIXEL 8u
#ifdef STAR_PIXELS
layout(std430, binding = STAR_ACCUMULATOR_BINDING) buffer StarAccumulator { uvec4 star_pixels[]; };

/// The 64-bit integer (low, high) in units of exposed radiance: high · 2³² +
/// low counts, each word converted once (the same float on every node).
float star_value(uint low, uint high) {
  return float(int(high)) * (4294967296.0 * STAR_UNIT_PER_COUNT) + float(low) * STAR_UNIT_PER_COUNT;
}
#else
layout(std430, binding = STAR_ACCUMULATOR_BINDING) buffer StarAccumulator { uint star_accumulator[]; };

/// Adds `value` (exposed radiance) to the 64-bit integer at words i (low) and
/// i + 1 (high): round(value · STAR_COUNTS_PER_UNIT) in two's complement.
void add_star_counts(uint i, float value) {
  const float counts = round(min(abs(value), STAR_RADIANCE_LIMIT) * STAR_COUNTS_PER_UNIT);  // an integer < 2^44
  if (counts == 0.0) return;
  // Its words: high = floor(counts / 2³²) exactly (a power-of-two scale), low
  // the rest, < 2³² and exact (counts has 24 significant bits, multiples of its ulp).
  const float high_words = floor(counts * (1.0 / 4294967296.0));
  uint low = uint(counts - high_words * 4294967296.0);
  uint high = uint(high_words);
  if (value < 0.0) {  // −(high · 2³² + low) = ~x + 1
    low = ~low + 1u;
    high = ~high + (low == 0u ? 1u : 0u);
  }
  const uint old = atomicAdd(star_accumulator[i], low);
  high += old + low < old ? 1u : 0u;  // the low word wrapped: carry one
  if (high != 0u) atomicAdd(star_accumulator[i + 1u], high);
}
#endif
