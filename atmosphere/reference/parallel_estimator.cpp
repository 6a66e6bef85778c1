#include "atmosphere/reference/parallel_estimator.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>

namespace zenith::atmosphere::reference {

namespace {

struct Moments {
  double count = 0.0, mean = 0.0, m2 = 0.0;  // m2 = Σ (x − mean)²

  void add(double x) {
    count += 1.0;
    const double delta = x - mean;
    mean += delta / count;
    m2 += delta * (x - mean);
  }
  void merge(const Moments& o) {
    if (o.count == 0.0) return;
    const double total = count + o.count;
    const double delta = o.mean - mean;
    mean += delta * (o.count / total);
    m2 += o.m2 + delta * delta * (count * o.count / total);
    count = total;
  }
};

}  // namespace

SampleMoments run_parallel_estimator(const ParallelEstimatorSettings& s, const SampleFunction& sample) {
  if (s.samples_per_wavelength == 0 || s.wavelength_count == 0 || s.components == 0)
    throw std::invalid_argument("run_parallel_estimator: need samples, wavelengths and components");
  const std::size_t chunks_per_wavelength = (s.samples_per_wavelength + kChunkSize - 1) / kChunkSize;
  const std::size_t chunk_count = chunks_per_wavelength * s.wavelength_count;
  // chunk_moments[chunk * components + component]
  std::vector<Moments> chunk_moments(chunk_count * s.components);

  std::atomic<std::size_t> next_chunk{0};
  std::atomic<bool> failed{false};
  std::exception_ptr failure;
  std::mutex failure_mutex;

  auto worker = [&] {
    std::vector<double> values(s.components);
    while (!failed.load(std::memory_order_relaxed)) {
      const std::size_t chunk = next_chunk.fetch_add(1);
      if (chunk >= chunk_count) return;
      const std::size_t wavelength = chunk / chunks_per_wavelength;
      const std::size_t first = (chunk % chunks_per_wavelength) * kChunkSize;
      const std::size_t last = std::min(first + kChunkSize, s.samples_per_wavelength);
      try {
        for (std::size_t j = first; j < last; ++j) {
          Pcg32 rng = Pcg32::for_sample(s.seed, wavelength, j);
          std::fill(values.begin(), values.end(), 0.0);
          sample(wavelength, j, rng, values);
          for (std::size_t c = 0; c < s.components; ++c) chunk_moments[chunk * s.components + c].add(values[c]);
        }
      } catch (...) {
        const std::lock_guard<std::mutex> lock(failure_mutex);
        if (!failure) failure = std::current_exception();
        failed = true;
        return;
      }
    }
  };

  unsigned threads = s.thread_count != 0 ? s.thread_count : std::max(1u, std::thread::hardware_concurrency());
  threads = unsigned(std::min<std::size_t>(threads, chunk_count));
  std::vector<std::thread> pool;
  for (unsigned k = 1; k < threads; ++k) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);

  SampleMoments result;
  result.mean.assign(s.components * s.wavelength_count, 0.0);
  result.standard_error.assign(s.components * s.wavelength_count, 0.0);
  for (std::size_t c = 0; c < s.components; ++c)
    for (std::size_t w = 0; w < s.wavelength_count; ++w) {
      Moments total;
      for (std::size_t k = 0; k < chunks_per_wavelength; ++k)
        total.merge(chunk_moments[(w * chunks_per_wavelength + k) * s.components + c]);
      const std::size_t index = c * s.wavelength_count + w;
      result.mean[index] = total.mean;
      result.standard_error[index] = total.count > 1.0 ? std::sqrt(total.m2 / (total.count - 1.0) / total.count) : 0.0;
    }
  return result;
}

}  // namespace zenith::atmosphere::reference
