// What a projection's tile cones cost (docs/rendering.md, "Skipping what a
// scene does not need"): built once per projection, on every core, before its
// first frame — part of a node's or an offline job's start.
//   build/bench/tile_cones_bench [--benchmark_out=FILE --benchmark_out_format=csv]
#include <benchmark/benchmark.h>

#include "render/frame/tile_culling.h"
#include "warp/fisheye_projection.h"
#include "warp/planar_projection.h"

namespace zenith::render {
namespace {

/// A 180° fisheye dome master of state.range(0)² pixels.
void BM_TileConesOfADomeMaster(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const warp::FisheyeProjection dome(n, n);
  for (auto _ : state) benchmark::DoNotOptimize(TileCones(dome));
  state.counters["tiles"] = static_cast<double>((n / kTileSize) * (n / kTileSize));
}
BENCHMARK(BM_TileConesOfADomeMaster)->Arg(2048)->Arg(4096)->Arg(8192)->Unit(benchmark::kMillisecond);

/// A 3840 × 2160 planar view, 90° across.
void BM_TileConesOfAPlanarView(benchmark::State& state) {
  const warp::PlanarProjection view = warp::PlanarProjection::symmetric(3840, 2160, 90.0);
  for (auto _ : state) benchmark::DoNotOptimize(TileCones(view));
}
BENCHMARK(BM_TileConesOfAPlanarView)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace zenith::render

BENCHMARK_MAIN();
