// Lookup tables: parameterization, CPU precompute, queries and the cache.
#include <gtest/gtest.h>

#include <unistd.h>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include "atmosphere/constants.h"
#include "atmosphere/lut/cpu_precompute.h"
#include "atmosphere/lut/lookup_tables.h"
#include "atmosphere/lut/quadrature.h"
#include "atmosphere/lut/series_tail.h"
#include "atmosphere/lut/table_cache.h"
#include "atmosphere/model_hash.h"
#include "atmosphere/parameters.h"
#include "tests/atmosphere/lut_fixture.h"

namespace zenith::atmosphere::lut {
namespace {

TEST(Parameterization, TransmittanceMappingRoundTrips) {
  for (const char* preset : {"earth-advanced", "mars", "titan"}) {
    const AtmosphereModel m = load_preset(preset).model;
    const ShellGeometry g{m.ground_radius_m, m.top_radius_m};
    const TableSizes s;
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int i = 0; i < 1000; ++i) {
      const double r = g.bottom_radius_m + u(rng) * (g.top_radius_m - g.bottom_radius_m);
      const double mu_horizon = -std::sqrt(1.0 - (g.bottom_radius_m / r) * (g.bottom_radius_m / r));
      const double mu = mu_horizon + u(rng) * (1.0 - mu_horizon);
      const TransmittanceUV uv = transmittance_uv(g, s, r, mu);
      double r2, mu2;
      transmittance_r_mu(g, s, uv.u_mu, uv.v_r, &r2, &mu2);
      EXPECT_NEAR(r2, r, 1e-6 * r) << preset;
      EXPECT_NEAR(mu2, mu, 1e-6) << preset << " r=" << r;
    }
  }
}

TEST(Parameterization, ScatteringTexelCentresMapBackToThemselves) {
  const AtmosphereModel m = load_preset("mars").model;
  const ShellGeometry g{m.ground_radius_m, m.top_radius_m};
  const TableSizes s = TableSizes::small();
  for (std::size_t z = 0; z < s.scattering_r; ++z)
    for (std::size_t y = 0; y < s.scattering_mu; ++y)
      for (std::size_t x = 0; x < s.scattering_mu_s; ++x) {  // ν index 0 (ν clamped, so skip ν)
        for (AngleMapping mapping : {AngleMapping::Distance, AngleMapping::Blended}) {
          const ScatteringCoordinates c = scattering_texel_coordinates(g, s, x, y, z, mapping);
          const ScatteringUVWZ uv = scattering_uvwz(g, s, c.r_m, c.mu, c.mu_s, c.nu, c.ray_hits_ground, mapping);
          EXPECT_NEAR(uv.u_r, (z + 0.5) / s.scattering_r, 1e-9);
          // At the ground (z = 0) every downward ray has length 0: that half is degenerate.
          if (z > 0 || !c.ray_hits_ground) {
            // (1e-6: the tangent ray, y = 0, is ill-conditioned: d depends on √disc with disc → 0.)
            EXPECT_NEAR(uv.u_mu, (y + 0.5) / s.scattering_mu, 1e-6) << z << " " << y;
          }
          EXPECT_NEAR(uv.u_mu_s, (x + 0.5) / s.scattering_mu_s, 1e-9);
          EXPECT_EQ(c.ray_hits_ground, y < s.scattering_mu / 2);
        }
      }
}

TEST(Parameterization, SunAngleRangeDerivesFromTheRadii) {
  // μs_min = cos(90° + 3α), α = acos(rb/rt), or −1 when 3α ≥ 90°: every preset.
  struct Expected {
    const char* preset;
    double min_sun_cosine, min_sun_zenith_deg;
  };
  for (const Expected& e :
       {Expected{"earth-standard", -0.5039, 120.26}, Expected{"earth-advanced", -0.5039, 120.26},
        Expected{"mars", -0.6593, 131.25}, Expected{"halcyon", -0.3773, 112.16}, Expected{"titan", -1.0, 180.0}}) {
    const AtmosphereModel m = load_preset(e.preset).model;
    const ShellGeometry g{m.ground_radius_m, m.top_radius_m};
    const double alpha = std::acos(m.ground_radius_m / m.top_radius_m);
    const double expected = 3.0 * alpha >= kPi / 2 ? -1.0 : std::cos(kPi / 2 + 3.0 * alpha);
    EXPECT_NEAR(g.min_sun_cosine(), expected, 1e-12) << e.preset;
    EXPECT_NEAR(g.min_sun_cosine(), e.min_sun_cosine, 1e-4) << e.preset;
    EXPECT_NEAR(std::acos(g.min_sun_cosine()) * 180.0 / kPi, e.min_sun_zenith_deg, 0.01) << e.preset;
  }
}

// geometric_blend (lookup_tables.h): exact for an exponential between two
// texels up to a ratio of e⁵, linear at zeros, and continuous as one side goes
// to zero (the fade to linear between |ln(b/a)| = 5 and 6).
TEST(GeometricBlend, ExactForExponentialsLinearAtZerosContinuousTowardZero) {
  for (double log_ratio : {-4.0, -1.0, 0.3, 2.0, 5.0})
    for (double t : {0.0, 0.25, 0.5, 0.9, 1.0})
      EXPECT_NEAR(geometric_blend(2.0, 2.0 * std::exp(log_ratio), t), 2.0 * std::exp(t * log_ratio),
                  2e-6 * 2.0 * std::exp(std::max(0.0, log_ratio)))
          << "ln(b/a) " << log_ratio << ", t " << t;
  EXPECT_DOUBLE_EQ(geometric_blend(0.0, 3.0, 0.25), 0.75);
  EXPECT_DOUBLE_EQ(geometric_blend(3.0, 0.0, 0.25), 2.25);
  // Beyond e⁶ the blend is linear: a vanishing neighbour does not pull the result to zero.
  EXPECT_DOUBLE_EQ(geometric_blend(1e-9, 1.0, 0.5), 0.5 * (1e-9 + 1.0));
  // Halfway through the fade (|ln(b/a)| = 5.5): the mean of the two forms.
  const double b = std::exp(5.5), linear = 0.5 * (1.0 + b), geometric = std::exp(2.75);
  EXPECT_NEAR(geometric_blend(1.0, b, 0.5), 0.5 * (linear + geometric), 1e-5 * linear);
}

// A table whose values fall by e² per μs texel (as twilight does at the paper's
// sizes) read between texel centres: the geometric read is exact, the linear
// read overshoots by cosh(1) − 1 ≈ 54 % at the midpoint.
TEST(GeometricBlend, ScatteringReadFollowsAnExponentialFallInMuS) {
  TableSizes s = TableSizes::small();
  Table3D table(s.scattering_width(), s.scattering_mu, s.scattering_r, 1);
  for (std::size_t z = 0; z < table.depth; ++z)
    for (std::size_t y = 0; y < table.height; ++y)
      for (std::size_t x = 0; x < table.width; ++x)
        table.texel(x, y, z)[0] = float(std::exp(-2.0 * double(x % s.scattering_mu_s)));
  const double n = double(s.scattering_mu_s);
  for (double column : {3.5, 10.25, 20.75}) {
    const ScatteringUVWZ uv{0.4, (column + 0.5) / n, 0.3, 0.6};
    double geometric = 0.0, linear = 0.0;
    sample_scattering_table_geometric_mu_s(table, s, uv, &geometric);
    sample_scattering_table(table, s, uv, &linear);
    const double expected = std::exp(-2.0 * column);
    EXPECT_NEAR(geometric / expected, 1.0, 1e-5) << "column " << column;
    EXPECT_GT(linear / expected, 1.05) << "column " << column;
  }
}

TEST(LookupTables, ZenithTransmittanceMatchesClosedForm) {
  for (const char* preset : {"earth-standard", "earth-advanced", "mars", "titan", "halcyon"}) {
    const auto& fixture = SmallTables::get(preset);
    const AtmosphereModel& m = fixture.model;
    const auto tau = m.zenith_optical_depth().total;
    double t[kMaxChannels];
    fixture.queries->transmittance_to_top(m.ground_radius_m, 1.0, t);
    for (std::size_t c = 0; c < m.wavelength_count(); ++c)
      EXPECT_NEAR(t[c], std::exp(-tau[c] * m.air_mass(m.ground_radius_m, 1.0)), 1e-6 + 1e-5 * t[c]) << preset;
  }
}

TEST(LookupTables, TransmittanceIsReciprocal) {
  const auto& f = SmallTables::get("earth-advanced");
  const ShellGeometry& g = f.tables.geometry;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 200; ++i) {
    // A segment from x (radius r, upward-ish μ) over distance d, then back.
    const double r = g.bottom_radius_m + 10.0 + u(rng) * 50e3;
    const double mu = 0.02 + 0.98 * u(rng);
    const double d = u(rng) * g.distance_to_top_m(r, mu);
    const double r_d = std::sqrt(d * d + 2.0 * r * mu * d + r * r);
    const double mu_d = (r * mu + d) / r_d;
    double forward[kMaxChannels], backward[kMaxChannels];
    f.queries->transmittance(r, mu, d, false, forward);
    f.queries->transmittance(r_d, -mu_d, d, g.ray_hits_ground(r_d, -mu_d), backward);
    for (std::size_t c = 0; c < f.tables.channels; ++c) EXPECT_NEAR(forward[c], backward[c], 5e-3) << r << " " << mu;
  }
}

TEST(LookupTables, EarthNoonSkyIsBlueAndOrdersShrink) {
  const auto& f = SmallTables::computed("earth-advanced");
  ASSERT_EQ(f.report.order_fraction.size(), 4u);
  const Vec3 observer{0.0, 0.0, f.model.ground_radius_m + 1.0};
  const Vec3 sun = direction_from_angles(30.0 * kPi / 180.0, 0.0);
  const Spectrum zenith = f.queries->sky_radiance(observer, {0.0, 0.0, 1.0}, sun);
  EXPECT_GT(zenith[2], zenith[1]);  // B > G > R
  EXPECT_GT(zenith[1], zenith[0]);
  for (double v : zenith) EXPECT_TRUE(std::isfinite(v) && v > 0.0);
  // Each order adds less than the one before.
  for (std::size_t i = 1; i < f.report.order_fraction.size(); ++i)
    EXPECT_LT(f.report.order_fraction[i], f.report.order_fraction[i - 1]);
}

/// Precompute options with these table sizes, at most `max_orders` orders and
/// `sphere_zenith_samples` sphere nodes, the rest default.
PrecomputeOptions options_of(const TableSizes& sizes, int max_orders, int sphere_zenith_samples) {
  PrecomputeOptions o;
  o.sizes = sizes;
  o.max_orders = max_orders;
  o.sphere_zenith_samples = sphere_zenith_samples;
  return o;
}

TEST(LookupTables, ToleranceStopsEarlyAndReportsOrders) {
  const AtmosphereModel m = load_preset("mars").model;
  PrecomputeOptions o = options_of(TableSizes{32, 8, 16, 4, 4, 16, 8, 4}, 30, 6);
  o.tolerance = 0.05;
  o.scattering_samples = 16;
  PrecomputeReport report;
  const LookupTables t = precompute_tables_cpu(m, o, &report);
  EXPECT_LT(report.orders_used, 30);
  EXPECT_GE(report.orders_used, 2);
  EXPECT_EQ(t.scattering_orders, report.orders_used);
  EXPECT_LT(report.order_fraction.back(), 0.05 / (1.0 - 0.05) + 1e-9);
}

// ---- The series tail (series_tail.h)

TEST(SeriesTail, SumsAGeometricSeriesOfOrdersExactly) {
  // Orders L_n = a·k^n per texel, k = 0.4 in channel 0 and 0.6 in channel 1,
  // every texel with its own a: the tail is Σ_{n>N} a k^n = L_N k / (1 − k).
  const int N = 5;
  Table2D last(3, 2, 2), before(3, 2, 2), sum(3, 2, 2);
  const double k[2] = {0.4, 0.6};
  double expected_total = 0.0;
  for (std::size_t t = 0; t < 6; ++t)
    for (std::size_t c = 0; c < 2; ++c) {
      const double a = 1.0 + double(t);
      before.data[t * 2 + c] = float(a * std::pow(k[c], N - 1));
      last.data[t * 2 + c] = float(a * std::pow(k[c], N));
      sum.data[t * 2 + c] = 10.0f;
      expected_total += a * std::pow(k[c], N + 1) / (1.0 - k[c]);
    }
  const double total = add_series_tail(last, before, sum);
  EXPECT_NEAR(total, expected_total, 1e-6 * expected_total);
  for (std::size_t t = 0; t < 6; ++t)
    for (std::size_t c = 0; c < 2; ++c) {
      const double tail = (1.0 + double(t)) * std::pow(k[c], N + 1) / (1.0 - k[c]);
      EXPECT_NEAR(last.data[t * 2 + c], tail, 1e-6 * tail) << "the last order is replaced by the tail";
      EXPECT_NEAR(sum.data[t * 2 + c], 10.0 + tail, 1e-6 * (10.0 + tail));
    }
}

TEST(SeriesTail, CapsATexelsRatioAtItsTablesAndNeverAboveNineTenths) {
  // Three texels at ratio 0.4 and one at 0.95 (a texel whose orders have not
  // settled): the table's ratio is Σlast/Σbefore, the odd texel's capped at 1.25× it.
  Table3D last(4, 1, 1, 1), before(4, 1, 1, 1), sum(4, 1, 1, 1);
  for (std::size_t t = 0; t < 3; ++t) {
    before.data[t] = 1.0f;
    last.data[t] = 0.4f;
  }
  before.data[3] = 1.0f;
  last.data[3] = 0.95f;
  const double table_ratio = (3 * double(0.4f) + double(0.95f)) / 4.0;
  const double cap = 1.25 * table_ratio;
  ASSERT_LT(cap, 0.95);
  add_series_tail(last, before, sum);
  EXPECT_NEAR(sum.data[0], 0.4 * 0.4 / 0.6, 1e-6);
  EXPECT_NEAR(sum.data[3], 0.95 * cap / (1.0 - cap), 1e-6);
  EXPECT_DOUBLE_EQ(series_tail_ratio_cap(10.0, 1.0), kSeriesTailMaxRatio);
  EXPECT_DOUBLE_EQ(series_tail_ratio_cap(0.5, 1.0), 0.625);
  EXPECT_DOUBLE_EQ(series_tail_factor(0.9, 1.0, kSeriesTailMaxRatio), 9.0);  // at most 9× the last order
}

TEST(SeriesTail, NoTailWhereEitherOrderHasNoLight) {
  EXPECT_EQ(series_tail_factor(0.0, 1.0, 0.9), 0.0);
  EXPECT_EQ(series_tail_factor(1.0, 0.0, 0.9), 0.0);
  EXPECT_EQ(series_tail_factor(-1e-9, 1.0, 0.9), 0.0);
  EXPECT_EQ(series_tail_factor(std::nan(""), 1.0, 0.9), 0.0);
  EXPECT_EQ(series_tail_ratio_cap(0.0, 1.0), 0.0);
  EXPECT_EQ(series_tail_ratio_cap(1.0, 0.0), 0.0);
  Table2D last(2, 1, 1), before(2, 1, 1), sum(2, 1, 1);
  last.data = {0.0f, 0.5f};
  before.data = {1.0f, 0.0f};
  EXPECT_EQ(add_series_tail(last, before, sum), 0.0);
  EXPECT_EQ(sum.data, (std::vector<float>{0.0f, 0.0f}));
  Table2D wrong(3, 1, 1);
  EXPECT_THROW(add_series_tail(last, before, wrong), std::invalid_argument);
}

TEST(RaySamples, CrowdTowardTheLowestPointAndEndAtTheRaysEnds) {
  const double d_m = 300e3, lowest_m = 120e3;
  EXPECT_DOUBLE_EQ(ray_sample_distance_m(0, 50, d_m, lowest_m), 0.0);
  EXPECT_DOUBLE_EQ(ray_sample_distance_m(50, 50, d_m, lowest_m), d_m);
  EXPECT_DOUBLE_EQ(ray_sample_distance_m(20, 50, d_m, lowest_m), lowest_m);  // s = 0.4 = lowest / d
  double previous_step = 1e30;
  for (int i = 1; i <= 20; ++i) {  // steps shrink toward the lowest point
    const double step = ray_sample_distance_m(i, 50, d_m, lowest_m) - ray_sample_distance_m(i - 1, 50, d_m, lowest_m);
    EXPECT_LT(step, previous_step) << i;
    previous_step = step;
  }
  // A stride of k through n samples is the rule with n / k samples.
  for (int j = 0; j <= 25; ++j)
    EXPECT_NEAR(ray_sample_distance_m(2 * j, 50, d_m, lowest_m), ray_sample_distance_m(j, 25, d_m, lowest_m), 1e-9);
}

TEST(RaySamples, CoarseRaysVisitEveryStrideAndTheEnd) {
  auto visited = [](int stride, int n) {
    std::vector<int> v;
    for (int i = 0; i <= n; i = next_ray_sample(i, stride, n)) v.push_back(i);
    return v;
  };
  EXPECT_EQ(visited(1, 4), (std::vector<int>{0, 1, 2, 3, 4}));
  EXPECT_EQ(visited(2, 6), (std::vector<int>{0, 2, 4, 6}));
  EXPECT_EQ(visited(2, 5), (std::vector<int>{0, 2, 4, 5}));
  EXPECT_EQ(visited(5, 5), (std::vector<int>{0, 5}));
  PrecomputeOptions o;
  EXPECT_EQ(o.ray_sample_stride(2), 1);
  EXPECT_EQ(o.ray_sample_stride(3), o.coarse_ray_stride);
  o.coarse_ray_stride = 0;
  EXPECT_THROW(check_precompute_options(o), std::invalid_argument);
  o.coarse_ray_stride = 2;
  o.coarse_ray_first_order = 1;
  EXPECT_THROW(check_precompute_options(o), std::invalid_argument);
}

TEST(LookupTables, CoarseRaysOfTheHigherOrdersMoveTheTablesByLessThanHalfAPerCent) {
  // Orders 3 and 4 along every 2nd sample against every sample: the multiple-
  // scattering table (orders 2-4) moves by far less than the tables' own error
  // against the path tracer (2-4 % RMS, docs/lookup-tables.md). Measured 0.27 %;
  // 1.2 % when the limb rays (coarse_ray_stride_for) were read coarsely too.
  const AtmosphereModel m = load_preset("earth-advanced").model;
  PrecomputeOptions o = options_of(TableSizes{64, 16, 32, 8, 8, 32, 16, 4}, 4, 8);
  o.coarse_ray_stride = 1;
  const LookupTables fine = precompute_tables_cpu(m, o);
  o.coarse_ray_stride = 2;
  const LookupTables coarse = precompute_tables_cpu(m, o);
  double sum_squares = 0.0, sum_reference = 0.0;
  for (std::size_t i = 0; i < fine.multiple.data.size(); ++i) {
    const double a = fine.multiple.data[i], b = coarse.multiple.data[i];
    sum_squares += (b - a) * (b - a);
    sum_reference += a * a;
  }
  const double relative_rms = std::sqrt(sum_squares / sum_reference);
  EXPECT_GT(relative_rms, 0.0);  // the stride is applied
  EXPECT_LT(relative_rms, 0.005);
}

TEST(TableCache, RoundTripAndCorruptionDetection) {
  const auto& f = SmallTables::get("mars");
  const auto dir = std::filesystem::temp_directory_path() / ("zenith-cache-test-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  const TableCache cache(dir);
  EXPECT_FALSE(cache.load(f.model, f.options).has_value());
  const auto path = cache.store(f.model, f.options, f.tables);
  ASSERT_TRUE(std::filesystem::exists(path));
  const auto loaded = cache.load(f.model, f.options);
  ASSERT_TRUE(loaded.has_value());
  EXPECT_EQ(loaded->multiple.data, f.tables.multiple.data);
  EXPECT_EQ(loaded->transmittance.data, f.tables.transmittance.data);
  EXPECT_EQ(loaded->scattering_orders, f.tables.scattering_orders);
  EXPECT_EQ(loaded->hash, lookup_table_hash(f.model));

  // Other options: another key, so not found.
  PrecomputeOptions other = f.options;
  other.max_orders += 1;
  EXPECT_FALSE(cache.load(f.model, other).has_value());

  // Truncated file: detected, reported, not used.
  const auto size = std::filesystem::file_size(path);
  std::filesystem::resize_file(path, size / 2);
  std::string problem;
  EXPECT_FALSE(cache.load(f.model, f.options, &problem).has_value());
  EXPECT_FALSE(problem.empty());

  // Flipped bits in the pixel data: the checksum catches them.
  cache.store(f.model, f.options, f.tables);
  {
    std::fstream file(path, std::ios::in | std::ios::out | std::ios::binary);
    file.seekp(std::streamoff(std::filesystem::file_size(path) - 100));
    const char junk[8] = {1, 2, 3, 4, 5, 6, 7, 8};
    file.write(junk, 8);
  }
  problem.clear();
  EXPECT_FALSE(cache.load(f.model, f.options, &problem).has_value());
  EXPECT_FALSE(problem.empty());
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace zenith::atmosphere::lut
