#pragma once
// Runs independent Monte Carlo samples on std::threads and reduces them
// deterministically.
//
// Samples are grouped in fixed chunks of kChunkSize consecutive sample indices
// of one wavelength; threads take chunks in any order, each chunk keeps its own
// running mean and sum of squared deviations (Welford), and after all threads
// have joined the chunks are merged in index order (Chan et al. 1979). Together
// with per-sample random streams (random.h) the result is bit-identical for
// every thread count.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "atmosphere/reference/random.h"

namespace zenith::atmosphere::reference {

/// One sample: wavelength index, sample index, its random stream; writes the
/// sample's value of each of the estimator's components into `values`.
using SampleFunction =
    std::function<void(std::size_t wavelength, std::size_t sample, Pcg32& rng, std::span<double> values)>;

struct SampleMoments {
  std::vector<double> mean;            ///< [component * wavelengths + wavelength]
  std::vector<double> standard_error;  ///< √(sample variance / N), same layout
};

struct ParallelEstimatorSettings {
  std::size_t wavelength_count = 1;
  std::size_t samples_per_wavelength = 1;
  std::size_t components = 1;
  std::uint64_t seed = 0;
  unsigned thread_count = 0;  ///< 0: std::thread::hardware_concurrency()
};

inline constexpr std::size_t kChunkSize = 256;

/// Runs `sample` for every (wavelength, sample index) and returns the mean and
/// standard error of the mean of each component at each wavelength. An
/// exception thrown by a sample stops the run and is rethrown here.
SampleMoments run_parallel_estimator(const ParallelEstimatorSettings& settings, const SampleFunction& sample);

}  // namespace zenith::atmosphere::reference
