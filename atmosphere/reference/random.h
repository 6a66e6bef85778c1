#pragma once
// Deterministic random numbers for the Monte Carlo reference.
//
// Every Monte Carlo sample owns an independent PCG32 stream whose state and
// stream selector are derived from (seed, wavelength index, sample index) by
// SplitMix64 hashing. A sample's random numbers therefore do not depend on
// which thread runs it or in which order: results are identical for any
// thread count.
#include <cstdint>

namespace zenith::atmosphere::reference {

/// SplitMix64 finalizer (Steele, Lea & Flood 2014): a bijective 64-bit mix.
constexpr std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

/// PCG32 (O'Neill 2014): 64-bit LCG state, XSH-RR output permutation, 2^63
/// selectable streams.
class Pcg32 {
 public:
  Pcg32(std::uint64_t initial_state, std::uint64_t stream) : increment_((stream << 1u) | 1u) {
    next_uint32();
    state_ += initial_state;
    next_uint32();
  }

  /// The stream of Monte Carlo sample `sample` at wavelength index `wavelength`.
  static Pcg32 for_sample(std::uint64_t seed, std::uint64_t wavelength, std::uint64_t sample) {
    std::uint64_t h = splitmix64(seed);
    h = splitmix64(h ^ (0xD1B54A32D192ED03ull * (wavelength + 1)));
    h = splitmix64(h ^ sample);
    return Pcg32(h, splitmix64(h ^ 0xDA3E39CB94B95BDBull));
  }

  std::uint32_t next_uint32() {
    const std::uint64_t old = state_;
    state_ = old * 6364136223846793005ull + increment_;
    const auto xorshifted = static_cast<std::uint32_t>(((old >> 18u) ^ old) >> 27u);
    const auto rotation = static_cast<std::uint32_t>(old >> 59u);
    return (xorshifted >> rotation) | (xorshifted << ((32u - rotation) & 31u));
  }

  /// Uniform double in [0, 1) with 53 random bits.
  double uniform() {
    const std::uint64_t high = next_uint32() >> 5u;  // 27 bits
    const std::uint64_t low = next_uint32() >> 6u;   // 26 bits
    return static_cast<double>((high << 26u) | low) * 0x1.0p-53;
  }

 private:
  std::uint64_t state_ = 0;
  std::uint64_t increment_;
};

}  // namespace zenith::atmosphere::reference
