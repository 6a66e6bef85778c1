// Cost of resolving parameter sets: what a show with parameter tracks pays per
// distinct atmosphere before any table is computed.
#include <benchmark/benchmark.h>

#include "atmosphere/model_hash.h"
#include "atmosphere/parameters.h"

namespace zenith::atmosphere {
namespace {

void BM_ResolvePreset(benchmark::State& state, const char* name) {
  const nlohmann::json params = preset_parameters(name);
  for (auto _ : state) benchmark::DoNotOptimize(resolve_atmosphere(params, name));
}
BENCHMARK_CAPTURE(BM_ResolvePreset, earth_standard, "earth-standard");
BENCHMARK_CAPTURE(BM_ResolvePreset, earth_advanced, "earth-advanced");
BENCHMARK_CAPTURE(BM_ResolvePreset, mars, "mars");

void BM_LookupTableHash(benchmark::State& state) {
  const AtmosphereModel m = load_preset("earth-advanced").model;
  for (auto _ : state) benchmark::DoNotOptimize(lookup_table_hash(m));
}
BENCHMARK(BM_LookupTableHash);

void BM_ExtinctionAtAltitude(benchmark::State& state) {
  const AtmosphereModel m = load_preset("earth-advanced").model;
  double h = 0.0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(m.extinction_m1(h));
    h = h > 9e4 ? 0.0 : h + 137.0;
  }
}
BENCHMARK(BM_ExtinctionAtAltitude);

}  // namespace
}  // namespace zenith::atmosphere

BENCHMARK_MAIN();
