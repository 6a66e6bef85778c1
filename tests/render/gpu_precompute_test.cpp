// The GPU lookup-table precomputation (render/lut/gpu_precompute.h) against the
// CPU one (atmosphere/lut/cpu_precompute.h): same options, same tables, same report.
//
// Agreement bound (fp64 shaders, the default), from the arithmetic:
//  * values above 1e-3 of the table's largest: 1e-5 relative. Both sides run
//    the same double operations in the same order; a driver whose sqrt, exp or
//    log is an ulp off (NVIDIA's fp64 sqrt is, driver 580.159.04) or that fuses
//    products into FMAs changes a double result by ~1e-16, which matters only
//    where it moves a float32 rounding: each stored table (transmittance,
//    single, then per order density, irradiance, multiple: 8 with 3 orders)
//    may then differ by 1 float ulp (1.2e-7) and pass it on through sums of
//    positive terms (condition number ~1): 8 × 1.2e-7 ≈ 1e-6, bound 1e-5.
//  * the others: 1e-3 / 20 = 5e-5 of the largest value. Such values come from
//    rays along the horizon or the terminator, where whether a sample of the
//    ray is lit (or its ray hits the ground) is decided by the last bit of a
//    sqrt: one sample of N ≥ 20 (the fewest any test here uses) flips, taking
//    at most its 1/N share of a value ≤ 1e-3 of the largest.
// Measured on Mesa llvmpipe: bit-identical tables. With sqrt, exp_r and log_r
// 1 ulp off (ULP_PERTURBATION, BoundsHoldWithTheElementaryFunctionsOneUlpOff):
// 7.4e-7 relative, 1.95e-7 of the largest value absolute (Mars irradiance);
// NVIDIA gave 1.3e-8 (Earth) and 2.5e-7 (Mars, 64 wavelengths) absolute.
// The fp32 fallback (geometry in float) is held to 1e-1 relative; measured 6e-2
// on the tiny tables below and 1.6e-2 on TableSizes::small(), at grazing rays
// near the ground.
#include "render/lut/gpu_precompute.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "atmosphere/lut/cpu_precompute.h"
#include "atmosphere/parameters.h"
#include "atmosphere/phase_functions.h"
#include "core/units.h"
#include "tests/render/shader_faults.h"
#include "tests/render/tiny_precompute_options.h"

namespace zenith::render {
namespace {

using atmosphere::AtmosphereModel;
using namespace atmosphere::lut;  // the tables, their sizes and the precompute's options and report

constexpr double kSignificant = 1e-3;  ///< of the table's largest value: compared relatively above it
constexpr double kRelativeBound = 1e-5;
constexpr double kAbsoluteBound = kSignificant / 20;  ///< of the table's largest value, below kSignificant
constexpr double kFp32RelativeBound = 1e-1;
constexpr double kFp32AbsoluteBound = 1e-4;

/// Difference of a GPU table from the CPU one.
struct Agreement {
  double max_relative = 0.0;       ///< over |cpu| > kSignificant · max
  double max_absolute = 0.0;       ///< |gpu − cpu| / max over the others
  std::size_t worst = 0;           ///< index of the largest relative difference
  std::size_t worst_absolute = 0;  ///< index of the largest absolute one
  double table_max = 0.0;
  bool identical = true;
};

Agreement compare(const std::vector<float>& gpu, const std::vector<float>& cpu) {
  Agreement a;
  if (gpu.size() != cpu.size()) {
    ADD_FAILURE() << "table sizes differ: GPU " << gpu.size() << ", CPU " << cpu.size();
    a.max_relative = INFINITY;
    return a;
  }
  for (float v : cpu) a.table_max = std::max(a.table_max, std::abs(static_cast<double>(v)));
  const double floor = kSignificant * a.table_max;
  for (std::size_t i = 0; i < cpu.size(); ++i) {
    const double c = cpu[i], g = gpu[i];
    if (gpu[i] != cpu[i]) a.identical = false;
    if (!std::isfinite(g)) {
      a.max_relative = INFINITY;
      a.worst = i;
    } else if (std::abs(c) > floor) {
      const double r = std::abs(g - c) / std::abs(c);
      if (r > a.max_relative) {
        a.max_relative = r;
        a.worst = i;
      }
    } else if (const double d = std::abs(g - c) / std::max(a.table_max, 1e-30); d > a.max_absolute) {
      a.max_absolute = d;
      a.worst_absolute = i;
    }
  }
  return a;
}

struct Result {
  LookupTables tables;
  PrecomputeReport report;
  std::vector<std::pair<std::string, double>> progress;
  double seconds = 0.0;
};

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

template <typename F>
Result timed_run(PrecomputeOptions options, F&& precompute) {
  Result run;
  options.progress = [&run](const PrecomputeProgress& p) { run.progress.emplace_back(p.stage, p.fraction); };
  const auto start = std::chrono::steady_clock::now();
  run.tables = precompute(options, &run.report);
  run.seconds = seconds_since(start);
  return run;
}

Result run_cpu(const AtmosphereModel& model, const PrecomputeOptions& options) {
  return timed_run(options, [&](const PrecomputeOptions& o, PrecomputeReport* r) {
    return atmosphere::lut::precompute_tables_cpu(model, o, r);
  });
}

Result run_gpu(const AtmosphereModel& model, const PrecomputeOptions& options,
               GpuPrecision precision = GpuPrecision::automatic, const gl::HeadlessContext* context = nullptr) {
  return timed_run(options, [&](const PrecomputeOptions& o, PrecomputeReport* r) {
    return precompute_tables_gpu(model, o, r, context, precision);
  });
}

/// The options of the comparison: small tables, 3 orders, a coarse sphere integral.
PrecomputeOptions small_options() {
  PrecomputeOptions o;
  o.sizes = TableSizes::small();
  o.max_orders = 3;
  o.sphere_zenith_samples = 8;
  return o;
}

/// Compares every table, the table-set metadata and the report; prints the agreement.
void expect_same_tables(const std::string& name, const Result& cpu, const Result& gpu,
                        double relative_bound = kRelativeBound, double absolute_bound = kAbsoluteBound) {
  const LookupTables &c = cpu.tables, &g = gpu.tables;
  EXPECT_EQ(g.channels, c.channels);
  EXPECT_EQ(g.sizes, c.sizes);
  EXPECT_EQ(g.geometry.bottom_radius_m, c.geometry.bottom_radius_m);
  EXPECT_EQ(g.geometry.top_radius_m, c.geometry.top_radius_m);
  EXPECT_EQ(g.scattering_orders, c.scattering_orders);
  EXPECT_EQ(g.hash, c.hash);
  const struct {
    const char* table;
    const std::vector<float>& gpu;
    const std::vector<float>& cpu;
  } tables[] = {{"transmittance", g.transmittance.data, c.transmittance.data},
                {"irradiance", g.irradiance.data, c.irradiance.data},
                {"single Rayleigh", g.single_rayleigh.data, c.single_rayleigh.data},
                {"single Mie", g.single_mie.data, c.single_mie.data},
                {"multiple", g.multiple.data, c.multiple.data}};
  std::printf("%s: CPU %.2f s, GPU %.2f s on %s\n", name.c_str(), cpu.seconds, gpu.seconds, gpu.report.device.c_str());
  for (const auto& t : tables) {
    const Agreement a = compare(t.gpu, t.cpu);
    std::printf("  %-16s %s max relative %.2e, max absolute %.2e of max %.4g\n", t.table,
                a.identical ? "identical," : "          ", a.max_relative, a.max_absolute, a.table_max);
    EXPECT_LE(a.max_relative, relative_bound)
        << name << ", " << t.table << ": value " << a.worst << " GPU " << t.gpu[a.worst] << " CPU " << t.cpu[a.worst];
    EXPECT_LE(a.max_absolute, absolute_bound) << name << ", " << t.table << ": value " << a.worst_absolute << " GPU "
                                              << t.gpu[a.worst_absolute] << " CPU " << t.cpu[a.worst_absolute];
  }

  // The report: the same stages in the same order, orders and their shares;
  // the stages are timed within the call, so together they took at most its wall time.
  ASSERT_EQ(gpu.report.stages.size(), cpu.report.stages.size());
  double stage_seconds = 0.0;
  for (std::size_t i = 0; i < cpu.report.stages.size(); ++i) {
    EXPECT_EQ(gpu.report.stages[i].stage, cpu.report.stages[i].stage);
    EXPECT_GE(gpu.report.stages[i].seconds, 0.0);
    stage_seconds += gpu.report.stages[i].seconds;
  }
  EXPECT_LE(stage_seconds, gpu.seconds);
  EXPECT_EQ(gpu.report.orders_used, cpu.report.orders_used);
  ASSERT_EQ(gpu.report.order_fraction.size(), cpu.report.order_fraction.size());
  for (std::size_t i = 0; i < cpu.report.order_fraction.size(); ++i)
    EXPECT_NEAR(gpu.report.order_fraction[i], cpu.report.order_fraction[i], 10 * relative_bound) << "order " << i + 1;
  EXPECT_NEAR(gpu.report.tail_fraction, cpu.report.tail_fraction, 10 * relative_bound);
  EXPECT_FALSE(gpu.report.device.empty());
  EXPECT_EQ(gpu.report.device.find("CPU ("), std::string::npos) << gpu.report.device;
  // Progress: the same calls (stage names and fractions) in the same order.
  EXPECT_EQ(gpu.progress, cpu.progress);
}

void compare_preset(const std::string& preset) {
  const AtmosphereModel model = atmosphere::load_preset(preset).model;
  const PrecomputeOptions options = small_options();
  const Result cpu = run_cpu(model, options);
  const Result gpu = run_gpu(model, options);
  expect_same_tables(preset, cpu, gpu);
  for (const auto& s : gpu.report.stages) std::printf("    %-34s %.3f s\n", s.stage.c_str(), s.seconds);
}

TEST(GpuPrecompute, MatchesCpuForEarthAdvanced) { compare_preset("earth-advanced"); }
TEST(GpuPrecompute, MatchesCpuForMars) { compare_preset("mars"); }
TEST(GpuPrecompute, MatchesCpuForTitan) { compare_preset("titan"); }

TEST(GpuPrecompute, FiveWavelengthsUseTwoGroupsOfFour) {
  atmosphere::LoadOptions load;
  load.wavelengths_nm = std::vector<double>{440, 500, 550, 600, 680};
  const AtmosphereModel model = atmosphere::load_preset("earth-advanced", load).model;
  ASSERT_EQ(model.wavelength_count(), 5u);
  PrecomputeOptions options = small_options();
  options.max_orders = 2;  // orders >= 3 with several groups: SixtyFourWavelengths
  const Result gpu = run_gpu(model, options);
  EXPECT_EQ(gpu.tables.channels, 5u);
  expect_same_tables("earth-advanced, 5 wavelengths", run_cpu(model, options), gpu);
}

TEST(GpuPrecompute, SixtyFourWavelengths) {
  std::vector<double> wavelengths;
  for (int i = 0; i < 64; ++i) wavelengths.push_back(440.0 + 4.0 * i);  // within the preset's tabulated range
  atmosphere::LoadOptions load;
  load.wavelengths_nm = wavelengths;
  const AtmosphereModel model = atmosphere::load_preset("mars", load).model;
  ASSERT_EQ(model.wavelength_count(), 64u);
  const PrecomputeOptions options = testing::tiny_precompute_options();
  expect_same_tables("mars, 64 wavelengths", run_cpu(model, options), run_gpu(model, options));
}

/// A model without aerosols: the Mie terms are compiled out of the shaders.
TEST(GpuPrecompute, NoMieVariantMatchesCpu) {
  AtmosphereModel model = atmosphere::load_preset("earth-advanced").model;
  for (std::size_t i = 0; i < model.wavelength_count(); ++i)
    model.mie_scattering_m1[i] = model.mie_extinction_m1[i] = 0.0;
  ASSERT_FALSE(model.has_mie());
  const PrecomputeOptions options = small_options();
  const Result cpu = run_cpu(model, options);
  const Result gpu = run_gpu(model, options);
  expect_same_tables("earth-advanced without Mie", cpu, gpu);
  for (float v : gpu.tables.single_mie.data) ASSERT_EQ(v, 0.0f);
}

/// Every switch of the shaders against the CPU, on tiny tables: phase functions,
/// absorbers, air mass, quadrature rule, a single order, the tolerance stop.
TEST(GpuPrecompute, ShaderVariantsMatchCpu) {
  struct Variant {
    std::string name;
    std::string preset;
    void (*edit)(AtmosphereModel&, PrecomputeOptions&);
  };
  const Variant variants[] = {
      {"halcyon (Cornette-Shanks, molecular absorption)", "halcyon", [](AtmosphereModel&, PrecomputeOptions&) {}},
      {"earth-standard (no absorbers)", "earth-standard", [](AtmosphereModel&, PrecomputeOptions&) {}},
      {"classic Rayleigh phase, no air mass, trapezoid", "earth-advanced",
       [](AtmosphereModel& m, PrecomputeOptions& o) {
         m.rayleigh_phase = atmosphere::RayleighPhaseModel::Classic;
         m.air_mass = atmosphere::AirMassStretch();
         o.scattering_quadrature = PrecomputeOptions::Quadrature::Trapezoid;
       }},
      {"one order, odd transmittance samples", "titan",
       [](AtmosphereModel&, PrecomputeOptions& o) {
         o.max_orders = 1;
         o.transmittance_samples = 51;
       }},
      {"tolerance stop", "earth-advanced",
       [](AtmosphereModel&, PrecomputeOptions& o) {
         // Tiny tables (4 r layers) converge slowly with the exact (harmonic)
         // sphere integral: orders 5–8 each add 3–6 % of the total.
         o.max_orders = 12;
         o.tolerance = 0.05;
       }},
      {"no series tail", "mars", [](AtmosphereModel&, PrecomputeOptions& o) { o.series_tail = false; }},
      {"tabulated Mie phase, two columns", "earth-advanced",
       [](AtmosphereModel& m, PrecomputeOptions&) {
         // A forward peak and a backward rise, different at 440 and 680 nm.
         std::vector<double> angles;
         for (int a = 0; a <= 180; a += 3) angles.push_back(a);
         std::vector<atmosphere::TabulatedPhase::Column> columns = {{440.0, {}}, {680.0, {}}};
         for (double a : angles) {
           const double c = std::cos(a * core::kPi / 180.0);
           columns[0].values.push_back(atmosphere::double_henyey_greenstein(c, 0.9, -0.3, 0.8));
           columns[1].values.push_back(atmosphere::double_henyey_greenstein(c, 0.8, -0.2, 0.9));
         }
         m.mie_phase.model = atmosphere::MiePhase::Model::Tabulated;
         m.mie_phase.table = std::make_shared<const atmosphere::TabulatedPhase>(angles, columns, m.wavelengths_nm);
       }},
  };
  for (const Variant& v : variants) {
    AtmosphereModel model = atmosphere::load_preset(v.preset).model;
    PrecomputeOptions options = testing::tiny_precompute_options();
    v.edit(model, options);
    const Result cpu = run_cpu(model, options);
    expect_same_tables(v.name, cpu, run_gpu(model, options));
    if (options.tolerance > 0.0) {
      EXPECT_GT(cpu.report.orders_used, 2);
      EXPECT_LT(cpu.report.orders_used, options.max_orders);  // the stop was exercised
    }
  }
}

/// RMS relative difference of the multiple-scattering tables where `reference` exceeds 1e-6 of its largest value.
double rms_relative(const std::vector<float>& values, const std::vector<float>& reference) {
  float largest = 0.0f;
  for (float v : reference) largest = std::max(largest, v);
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < reference.size(); ++i) {
    if (!(reference[i] > 1e-6f * largest)) continue;
    const double e = (double(values[i]) - reference[i]) / reference[i];
    sum += e * e;
    ++n;
  }
  return n ? std::sqrt(sum / double(n)) : 0.0;
}

TEST(GpuPrecompute, TheSeriesTailBringsFiveOrdersCloserToTheConvergedSeriesThanEightWithoutIt) {
  // Earth, small tables: the multiple-scattering table of 5 orders and the
  // tail against 20 orders without it (orders after 20 add < 1e-7), next to 5
  // and 8 orders without the tail. Measured (bench/series_tail_bench, small
  // tables, the total in-scattered radiance): 5 orders 2.5 %, 8 orders 0.32 %,
  // 5 orders and the tail 0.21 % RMS; of the multiple-scattering part alone,
  // printed below.
  const AtmosphereModel model = atmosphere::load_preset("earth-advanced").model;
  PrecomputeOptions o;
  o.sizes = TableSizes::small();
  o.series_tail = false;
  o.max_orders = 20;
  const LookupTables converged = run_gpu(model, o).tables;
  o.max_orders = 8;
  const double eight = rms_relative(run_gpu(model, o).tables.multiple.data, converged.multiple.data);
  o.max_orders = 5;
  const double five = rms_relative(run_gpu(model, o).tables.multiple.data, converged.multiple.data);
  o.series_tail = true;
  const Result tail = run_gpu(model, o);
  const double five_and_tail = rms_relative(tail.tables.multiple.data, converged.multiple.data);
  std::printf(
      "multiple scattering against 20 orders, RMS: 5 orders %.4f, 8 orders %.4f, 5 orders and the tail %.4f "
      "(the tail %.2f %% of the radiance)\n",
      five, eight, five_and_tail, 100.0 * tail.report.tail_fraction);
  EXPECT_LT(five_and_tail, eight);
  EXPECT_LT(five_and_tail, 0.15 * five);
  // Orders 6–∞ of Earth's radiance: about 1 % (orders 6, 7, 8 without the tail: 0.46, 0.19, 0.08 %).
  EXPECT_GT(tail.report.tail_fraction, 0.005);
  EXPECT_LT(tail.report.tail_fraction, 0.02);
  EXPECT_EQ(tail.report.orders_used, 5);
}

/// NVIDIA's fp64 on llvmpipe: sqrt, exp_r and log_r 1 ulp away from zero, then 1
/// ulp toward it (tests/render/shader_faults.h). NVIDIA's sqrt is
/// not correctly rounded (driver 580.159.04: 1 ulp) and its compiler may fuse
/// the series of exp_r and log_r into FMAs. The bounds at the top must hold.
TEST(GpuPrecompute, BoundsHoldWithTheElementaryFunctionsOneUlpOff) {
  for (const auto& [preset, ulps] : {std::pair<const char*, int>{"mars", 1}, {"earth-advanced", -1}}) {
    const AtmosphereModel model = atmosphere::load_preset(preset).model;
    const PrecomputeOptions options = small_options();
    const Result cpu = run_cpu(model, options);
    const testing::ScopedShaderFaults perturbed(testing::ShaderFaults::ulps_off(ulps));
    expect_same_tables(std::string(preset) + ", sqrt/exp/log " + std::to_string(ulps) + " ulp", cpu,
                       run_gpu(model, options));
  }
}

TEST(GpuPrecompute, Fp32FallbackAgreesLoosely) {
  const AtmosphereModel model = atmosphere::load_preset("earth-advanced").model;
  const PrecomputeOptions options = testing::tiny_precompute_options();
  expect_same_tables("earth-advanced, fp32 shaders", run_cpu(model, options),
                     run_gpu(model, options, GpuPrecision::fp32), kFp32RelativeBound, kFp32AbsoluteBound);
}

TEST(GpuPrecompute, UsesAGivenContextAndLeavesItCurrent) {
  const gl::HeadlessContext context;
  const AtmosphereModel model = atmosphere::load_preset("mars").model;
  const PrecomputeOptions options = testing::tiny_precompute_options();
  const Result gpu = run_gpu(model, options, GpuPrecision::automatic, &context);
  EXPECT_TRUE(context.is_current());
  EXPECT_EQ(gpu.report.device, context.renderer());
  expect_same_tables("mars, given context", run_cpu(model, options), gpu);
}

/// The programs' builds started all at once (the default, on the driver's
/// compiler threads where it has them; on llvmpipe the later stages' first
/// dispatches warmed on a second thread too), one at a time where first used
/// (gl::CompileMode::serial) or all at once on threads with a context each
/// (gl::CompileMode::contexts) are the same programs from the same texts: the
/// tables agree bit for bit, whatever the driver's arithmetic. With the
/// series tail (its program started ahead too) and with a tolerance that stops
/// before the last order (the builds started for orders never reached are abandoned).
TEST(GpuPrecompute, EveryCompileModeGivesTheSameTablesBitForBit) {
  const AtmosphereModel model = atmosphere::load_preset("earth-advanced").model;
  PrecomputeOptions options = testing::tiny_precompute_options();
  options.max_orders = 4;
  for (const double tolerance : {0.0, 0.5}) {
    options.tolerance = tolerance;
    PrecomputeReport serial_report;
    const LookupTables serial = precompute_tables_gpu(model, options, &serial_report, nullptr, GpuPrecision::automatic,
                                                      {}, gl::CompileMode::serial);
    if (tolerance > 0.0) {
      EXPECT_LT(serial.scattering_orders, options.max_orders);
    }
    for (const gl::CompileMode mode : {gl::CompileMode::parallel, gl::CompileMode::contexts}) {
      SCOPED_TRACE(fmt::format("tolerance {}, {}", tolerance, to_string(mode)));
      PrecomputeReport report;
      const LookupTables tables =
          precompute_tables_gpu(model, options, &report, nullptr, GpuPrecision::automatic, {}, mode);
      EXPECT_EQ(tables.scattering_orders, serial.scattering_orders);
      EXPECT_EQ(tables.transmittance.data, serial.transmittance.data);
      EXPECT_EQ(tables.irradiance.data, serial.irradiance.data);
      EXPECT_EQ(tables.single_rayleigh.data, serial.single_rayleigh.data);
      EXPECT_EQ(tables.single_mie.data, serial.single_mie.data);
      EXPECT_EQ(tables.multiple.data, serial.multiple.data);
      EXPECT_EQ(report.order_fraction, serial_report.order_fraction);
    }
  }
}

TEST(GpuPrecompute, RejectsBadOptionsLikeTheCpu) {
  const AtmosphereModel model = atmosphere::load_preset("mars").model;
  PrecomputeOptions options = testing::tiny_precompute_options();
  options.max_orders = 0;
  EXPECT_THROW(precompute_tables_gpu(model, options), std::invalid_argument);
  options = testing::tiny_precompute_options();
  options.sizes.scattering_mu = 9;  // odd
  EXPECT_THROW(precompute_tables_gpu(model, options), std::invalid_argument);
  EXPECT_STREQ(to_string(GpuPrecision::fp64), "fp64");
}

}  // namespace
}  // namespace zenith::render
