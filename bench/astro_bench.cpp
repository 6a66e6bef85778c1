// What the sky's ephemeris costs a frame (docs/night-sky.md, "Positions"):
// a SkyPositions made for an instant and a site, and the places read from it.
//   build/bench/astro_bench [--benchmark_out=FILE --benchmark_out_format=csv]
#include <benchmark/benchmark.h>

#include "astro/civil_time.h"
#include "astro/sky_positions.h"

namespace zenith::astro {
namespace {

const Site kSite{40.78, -73.97, 30.0};  // the Hayden Planetarium
const AstroTime kTime = AstroTime::from_utc({2026, 8, 12, 18, 30, 0.0});

/// Each iteration a new instant, 1/60 s on: a frame's ephemeris.
void BM_SkyPositionsOfAFrame(benchmark::State& state) {
  double t = 0.0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(SkyPositions(kTime.plus_seconds(t), kSite));
    t += 1.0 / 60.0;
  }
}
BENCHMARK(BM_SkyPositionsOfAFrame);

void BM_MoonPlace(benchmark::State& state) {
  const SkyPositions sky(kTime, kSite);
  for (auto _ : state) benchmark::DoNotOptimize(sky.moon());
}
BENCHMARK(BM_MoonPlace);

void BM_SunPlace(benchmark::State& state) {
  const SkyPositions sky(kTime, kSite);
  for (auto _ : state) benchmark::DoNotOptimize(sky.sun());
}
BENCHMARK(BM_SunPlace);

}  // namespace
}  // namespace zenith::astro

BENCHMARK_MAIN();
