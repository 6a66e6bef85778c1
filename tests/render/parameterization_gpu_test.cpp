// The table parameterization of shaders/atmosphere_common.glsl against the C++
// one it mirrors (atmosphere/lut/parameterization.h), on the GPU, where the
// mappings are least forgiving: μ at the horizon and 1e-6 either side of it
// (μ_h = −√(1 − (rb/r)²)) at the ground, 1 m and 10 m above it (there also
// 20 rays within 0.2 % of μ_h), mid-shell, 1 m below the top and at the top; μs at μs_min
// (ShellGeometry::min_sun_cosine), 1e-6 above it, below it (clamped), at the horizon and the zenith; ν at both ends of
// the range that μ and μs allow and between (u_ν = φ/π, the azimuth between view and sun); view and sun at the zenith
// (μ = ±1, μs = 1, where every ν is u_ν = 0); both angle mappings; scattering_u_mu for rays that hit the ground and
// rays that do not, both at the horizon itself. Then the inverse texel functions: transmittance_r_mu, irradiance_r_mu_s
// at the C++ coordinates, and scattering_texel_coordinates (μs and sky μ found by bisection in texel_coordinates.comp,
// ν from scattering_nu_from_unit) for every texel of the lowest and highest r layers. Earth and Mars presets,
// TableSizes::small().
//
// Tolerances (|GPU − C++| ≤ tolerance · max(1, |C++|): absolute for the unit
// coordinates, relative for r in metres):
//  * fp64: 1e-12. The shaders repeat the C++ operations in double in the same
//    order; only acos and cos differ (acos_r, cos_r of atmosphere_common.glsl,
//    within a few ulp of the C library: the blended μ and μs mappings, u_ν,
//    the texels' ν). Measured on Mesa llvmpipe (Mesa 22.3.6): every function
//    at the edge cases within 1.2e-16 (most bit-identical), the texel
//    coordinates within 1.2e-15. transmittance_r_mu's μ near the top, where
//    the law of cosines divides a cancelling numerator by a short chord, gets
//    transmittance_mu_bound on top. The ...WithSqrtOneUlpOff tests run the
//    same with sqrt, exp_r and log_r 1 ulp off (tests/render/shader_faults.h), as NVIDIA's
//    fp64 sqrt is: every function within 1e-15 but that μ (6.3e-11 Earth,
//    3.3e-11 Mars, at 1 m below the top).
//  * fp32: 1e-2, and 5e-2 for transmittance_r_mu's μ (a cancelling numerator
//    over a 1 m chord at the top, as in fp64 but with float's 2^-24: measured
//    7.5e-3). Geometry in float: near the ground r² − rb² is a few ulp of
//    r² (1 m above Mars' ground: 6 ulp), so it is computed as (r − rb)(r + rb)
//    (difference_of_squares, parameterization.cpp): its factors are exact and
//    a few float ulp, so the discriminant r²μ² − ρ² is within ~2 m² and the
//    distance to the ground within √2 m of its 2600 m range 1 m above Mars'
//    ground (u_μ within 3e-4). Written as r²μ² − r² + rb², u_μ next to the
//    horizon was off by 0.029 on llvmpipe (the 20-ray fan 1 m and 10 m up;
//    up to 0.15 over a denser fan in a float emulation) and 0.204 on NVIDIA
//    (whose compiler fuses the products into FMAs). Measured now
//    (llvmpipe): u_μ 1.6e-4, transmittance_r_mu's μ 7.5e-3 (Earth) and
//    4.6e-3 (Mars) 1 m below the top (the law of cosines over a 1 m chord),
//    texel ν 2.7e-4, the rest ≤ 2.3e-4. ray_hits_ground is not compared within
//    1e-5 of the horizon, where float rounding decides it. The C++ reference
//    is evaluated at the inputs rounded to float, so input rounding is not counted.
#include <gtest/gtest.h>

#include <epoxy/gl.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "atmosphere/lut/parameterization.h"
#include "atmosphere/parameters.h"
#include "render/gl/buffer.h"
#include "render/gl/shader_program.h"
#include "render/lut/shader_model.h"
#include "render/shader_bindings.h"
#include "render/shader_programs.h"
#include "tests/render/render_test_support.h"
#include "tests/render/shader_faults.h"
#include "tests/render/test_shaders.h"

namespace zenith::render {
namespace {

using atmosphere::lut::AngleMapping;
using atmosphere::lut::ShellGeometry;
using atmosphere::lut::TableSizes;

constexpr double kFp64Tolerance = 1e-12;
constexpr double kFp32Tolerance = 1e-2;
/// fp32, transmittance_r_mu's μ: the law of cosines over a chord of 1 m at the top.
constexpr double kFp32TopTolerance = 5e-2;
/// fp32: within this of the horizon, ray_hits_ground may go either way (r²(μ² − 1) + rb² cancels).
constexpr double kFp32HorizonBand = 1e-5;
constexpr int kRayHitsGround = 17;      ///< its index in kQuantities
constexpr int kUvwzUNu = 8, kUNu = 15;  ///< the u_ν quantities' indices in kQuantities
constexpr int kTransmittanceMu = 3;     ///< transmittance_r_mu's μ in kQuantities

double ulp(double x) { return std::nextafter(std::abs(x), INFINITY) - std::abs(x); }

/// The error bound of transmittance_r_mu's μ = (H² − ρ² − d²) / (2 r d) (the law
/// of cosines at the top), fp64, beyond kFp64Tolerance. The numerator cancels:
/// H², ρ² and d² each carry a few ulp of H² (8 ulp(H²) in all), divided by
/// 2 r d; and r = √(ρ² + rb²) from a sqrt 1 ulp off (NVIDIA's, or any that is
/// not correctly rounded) moves d_min = rt − r, hence d, by ulp(r): μ by
/// 2 ulp(r) / d. Both grow as the chord d shrinks: 1 m below the top, at μ = 1,
/// Earth 2.5e-9, Mars 1.2e-9; at d = 100 km, 1e-14 (NVIDIA gave 6.1e-12 there;
/// llvmpipe with ULP perturbation 6.3e-11 at μ = 0.25, d = 4 m).
double transmittance_mu_bound(const ShellGeometry& g, double r, double mu) {
  const double d = g.distance_to_top_m(r, mu);
  if (d <= 0.0) return 0.0;  // μ = 1 exactly on both sides
  const double H = g.horizon_distance_at_top_m();
  return 8.0 * ulp(H * H) / (2.0 * r * d) + 2.0 * ulp(r) / d;
}

// The test shader's buffers (not atmosphere_common.glsl's 0–2) and strides.
constexpr unsigned kCasesBinding = 3, kResultsBinding = 4;
constexpr int kCaseStride = 11, kResultStride = 19;

/// The quantities of one mode-0 result, in the shader's order.
constexpr const char* kQuantities[kResultStride] = {
    "transmittance_uv u_mu",   "transmittance_uv v_r",   "transmittance_r_mu r", "transmittance_r_mu mu",
    "irradiance_uv u_mu_s",    "irradiance_uv v_r",      "irradiance_r_mu_s r",  "irradiance_r_mu_s mu_s",
    "scattering_uvwz u_nu",    "scattering_uvwz u_mu_s", "scattering_uvwz u_mu", "scattering_uvwz u_r",
    "scattering_u_r",          "scattering_u_mu",        "scattering_u_mu_s",    "scattering_u_nu",
    "scattering_nu_from_unit", "ray_hits_ground",        "min_sun_cosine"};
constexpr const char* kTexelQuantities[5] = {"texel r", "texel mu", "texel mu_s", "texel nu", "texel hits_ground"};
constexpr int kTexelMu = 1, kTexelMuS = 2, kTexelNu = 3;  ///< their indices

struct Case {
  double r, mu, mu_s, nu;
  bool hits_ground;
  AngleMapping mapping;
  double x_nu;        ///< the input of scattering_nu_from_unit
  double horizon_mu;  ///< μ_h at r
};

double clamp_cosine(double x) { return std::clamp(x, -1.0, 1.0); }

/// The cases described at the top, for a shell.
std::vector<Case> edge_cases(const ShellGeometry& g) {
  const double rb = g.bottom_radius_m, rt = g.top_radius_m;
  const double mu_s_min = g.min_sun_cosine();
  std::vector<Case> cases;
  for (double r : {rb, rb + 1.0, rb + 10.0, 0.5 * (rb + rt), rt - 1.0, rt}) {
    const double mu_h = -std::sqrt(std::max(0.0, 1.0 - (rb / r) * (rb / r)));
    std::vector<double> mus = {mu_h - 1e-6, mu_h, mu_h + 1e-6, -1.0, 1.0, 0.25};
    // Just above the ground, a fan of rays within 0.2 % of the horizon's μ: where
    // r²μ² − (r² − rb²) cancels (difference_of_squares, parameterization.cpp).
    if (r > rb && r < rb + 100.0)
      for (int k = -10; k <= 10; ++k)
        if (k != 0) mus.push_back(mu_h * (1.0 + 2e-4 * k));
    for (double mu : mus) {
      mu = clamp_cosine(mu);
      std::vector<bool> flags = {g.ray_hits_ground(r, mu)};
      if (mu == mu_h) flags.push_back(!flags[0]);  // the horizon: both halves of the table
      for (bool hits : flags)
        for (double mu_s : {mu_s_min, mu_s_min + 1e-6, mu_s_min - 1e-3, 0.0, 0.5, 1.0}) {
          mu_s = clamp_cosine(mu_s);
          const double spread = std::sqrt(std::max(0.0, (1.0 - mu * mu) * (1.0 - mu_s * mu_s)));
          const double nus[3] = {clamp_cosine(mu * mu_s + spread), mu * mu_s, clamp_cosine(mu * mu_s - spread)};
          for (int k = 0; k < 3; ++k)
            for (AngleMapping mapping : {AngleMapping::Distance, AngleMapping::Blended})
              cases.push_back({r, mu, mu_s, nus[k], hits, mapping, 0.5 * k, mu_h});
        }
    }
  }
  return cases;
}

/// The worst difference of one quantity.
struct Worst {
  double difference = 0.0;
  std::string where;
};

class GpuParameterization {
 public:
  /// `shared`: the test program built as the render passes' programs are
  /// (ShaderModel::shared_defines: the model read from WavelengthData's header).
  GpuParameterization(const atmosphere::AtmosphereModel& model, const TableSizes& sizes, bool fp64, bool shared = false)
      : fp64_(fp64), sizes_(sizes) {
    testing::context();
    atmosphere::lut::PrecomputeOptions options;
    options.sizes = sizes;
    const ShaderModel m = shader_model(model, options, fp64);
    model_buffers_ = ModelBuffers(m);
    texel_values_ = gl::Buffer(m.texel_layout.count * real_size());
    model_buffers_.bind();
    texel_values_.bind_storage(binding::kTexelCoordinates);
    // As the precompute does before its scattering stages.
    load_compute_program("texel_coordinates.comp", m.defines).dispatch_covering(static_cast<int>(m.texel_layout.count));
    glMemoryBarrier(GL_ALL_BARRIER_BITS);
    std::vector<gl::ShaderDefine> defines = shared ? m.shared_defines : m.defines;
    defines.insert(defines.end(), {{"CASES_BINDING", std::to_string(kCasesBinding)},
                                   {"RESULTS_BINDING", std::to_string(kResultsBinding)},
                                   {"CASE_STRIDE", std::to_string(kCaseStride)},
                                   {"RESULT_STRIDE", std::to_string(kResultStride)}});
    program_ = testing::load_test_compute_program("test_parameterization.comp", defines);
  }

  /// The input as the shader holds it (rounded to float in fp32).
  double real(double v) const { return fp64_ ? v : static_cast<double>(static_cast<float>(v)); }

  /// Runs `mode` over `inputs` (kCaseStride reals per case); kResultStride reals per case back.
  std::vector<double> run(int mode, const std::vector<double>& inputs) const {
    const std::size_t count = inputs.size() / kCaseStride;
    const gl::Buffer in = real_buffer(inputs, fp64_);
    const gl::Buffer out(count * kResultStride * real_size());
    in.bind_storage(kCasesBinding);
    out.bind_storage(kResultsBinding);
    program_.set_uniform("case_count", static_cast<int>(count));
    program_.set_uniform("mode", mode);
    program_.dispatch_covering(static_cast<int>(count));
    glMemoryBarrier(GL_ALL_BARRIER_BITS);
    if (fp64_) return out.read<double>();
    const std::vector<float> f = out.read<float>();
    return std::vector<double>(f.begin(), f.end());
  }

  const TableSizes& sizes() const { return sizes_; }

 private:
  std::size_t real_size() const { return fp64_ ? sizeof(double) : sizeof(float); }
  bool fp64_;
  TableSizes sizes_;
  ModelBuffers model_buffers_;
  gl::Buffer texel_values_;
  gl::ShaderProgram program_;
};

/// How many representable floats lie between `a` and `b` (as floats).
std::int64_t float_steps_apart(double a, double b) {
  const auto ordered = [](float f) {
    const auto bits = std::bit_cast<std::int32_t>(f);
    return bits < 0 ? std::int64_t{std::numeric_limits<std::int32_t>::min()} - bits : std::int64_t{bits};
  };
  return std::abs(ordered(static_cast<float>(a)) - ordered(static_cast<float>(b)));
}

std::string describe(const Case& c) {
  char text[256];
  std::snprintf(text, sizeof text, "r=%.17g mu=%.17g mu_s=%.17g nu=%.17g hits_ground=%d mapping=%s x_nu=%g", c.r, c.mu,
                c.mu_s, c.nu, c.hits_ground ? 1 : 0, c.mapping == AngleMapping::Distance ? "distance" : "blended",
                c.x_nu);
  return text;
}

/// Checks every quantity of every case within `tolerance`; prints the worst
/// difference of each (the measured figures of the comment at the top).
/// `shared`: also the render passes' shared program (ShaderModel::shared_defines),
/// which must give the precompute program's values. On a software driver
/// (llvmpipe) they are the same bits in fp32 (its H and A computed on the CPU
/// in float as that compiler folds them) and within an ulp in fp64 (there the
/// precompute's H is the driver's double sqrt). A GPU's compiler folds the
/// precompute's constants its own way and its sqrt is not correctly rounded:
/// on NVIDIA's (H200, 580.159.04) the two programs differ by up to 4.8e4
/// float steps at transmittance_r_mu's μ near μ = 1 and 2.6e-8 at a texel's ν
/// by its ends, where these functions are ill conditioned. There each program
/// is held to the bounds against C++ below (the precompute's by the tests
/// without `shared`), and the largest difference of each quantity is printed.
void compare_parameterization(const std::string& preset, bool fp64, double tolerance, int ulp_perturbation = 0,
                              bool shared = false) {
  SCOPED_TRACE(preset + (fp64 ? " fp64" : " fp32") +
               (ulp_perturbation ? ", sqrt/exp/log " + std::to_string(ulp_perturbation) + " ulp" : "") +
               (shared ? ", shared render program" : ""));
  const atmosphere::AtmosphereModel model = atmosphere::load_preset(preset).model;
  const ShellGeometry g{model.ground_radius_m, model.top_radius_m};
  const testing::ScopedShaderFaults perturbed(testing::ShaderFaults::ulps_off(ulp_perturbation));
  const GpuParameterization gpu(model, TableSizes::small(), fp64, shared);
  std::optional<GpuParameterization> precompute;
  if (shared) precompute.emplace(model, TableSizes::small(), fp64, false);
  const auto same_as_precompute = [&](int mode, const std::vector<double>& inputs, const std::vector<double>& results) {
    if (!precompute) return;
    const std::vector<double> reference = precompute->run(mode, inputs);
    ASSERT_EQ(reference.size(), results.size());
    std::size_t differing = 0;
    double worst[kResultStride] = {};
    std::int64_t worst_steps[kResultStride] = {};
    for (std::size_t i = 0; i < results.size(); ++i) {
      const double d = std::abs(results[i] - reference[i]) / std::max(1.0, std::abs(reference[i]));
      if (fp64 ? d > 4e-16 : results[i] != reference[i]) ++differing;
      const std::size_t q = i % kResultStride;
      worst[q] = std::max(worst[q], d);
      worst_steps[q] = std::max(worst_steps[q], float_steps_apart(results[i], reference[i]));
    }
    std::printf(
        "mode %d, the shared program against the precompute's: %zu of %zu values differ; the largest "
        "difference of each output (relative to max(1, |value|); float steps):",
        mode, differing, results.size());
    for (int q = 0; q < kResultStride; ++q) std::printf(" %d: %.3g (%lld)", q, worst[q], (long long)worst_steps[q]);
    std::printf("\n");
    if (testing::context().is_software()) {
      EXPECT_EQ(differing, 0u) << "mode " << mode << ": values of the shared program not those of the precompute's";
    }
  };
  const TableSizes& s = gpu.sizes();

  // Mode 0: the functions at the edge cases (inputs rounded to what the shader holds).
  std::vector<Case> cases = edge_cases(g);
  for (Case& c : cases) {
    c.r = gpu.real(c.r);
    c.mu = gpu.real(c.mu);
    c.mu_s = gpu.real(c.mu_s);
    c.nu = gpu.real(c.nu);
  }
  std::vector<double> inputs, expected;
  for (const Case& c : cases) {
    const atmosphere::lut::TransmittanceUV t = atmosphere::lut::transmittance_uv(g, s, c.r, c.mu);
    const atmosphere::lut::IrradianceUV e = atmosphere::lut::irradiance_uv(g, s, c.r, c.mu_s);
    const double t_u = gpu.real(t.u_mu), t_v = gpu.real(t.v_r), e_u = gpu.real(e.u_mu_s), e_v = gpu.real(e.v_r);
    inputs.insert(inputs.end(), {c.r, c.mu, c.mu_s, c.nu, c.hits_ground ? 1.0 : 0.0,
                                 c.mapping == AngleMapping::Distance ? 0.0 : 1.0, t_u, t_v, e_u, e_v, c.x_nu});
    double t_r, t_mu, e_r, e_mu_s;
    atmosphere::lut::transmittance_r_mu(g, s, t_u, t_v, &t_r, &t_mu);
    atmosphere::lut::irradiance_r_mu_s(g, s, e_u, e_v, &e_r, &e_mu_s);
    const atmosphere::lut::ScatteringUVWZ uv =
        atmosphere::lut::scattering_uvwz(g, s, c.r, c.mu, c.mu_s, c.nu, c.hits_ground, c.mapping);
    expected.insert(expected.end(),
                    {t.u_mu, t.v_r, t_r, t_mu, e.u_mu_s, e.v_r, e_r, e_mu_s, uv.u_nu, uv.u_mu_s, uv.u_mu, uv.u_r,
                     uv.u_r, uv.u_mu, atmosphere::lut::scattering_u_mu_s(g, s, c.mu_s, c.mapping),
                     atmosphere::lut::scattering_u_nu(c.mu, c.mu_s, c.nu),
                     atmosphere::lut::scattering_nu_from_unit(c.mu, c.mu_s, c.x_nu),
                     g.ray_hits_ground(c.r, c.mu) ? 1.0 : 0.0, g.min_sun_cosine()});
  }
  const std::vector<double> results = gpu.run(0, inputs);
  ASSERT_EQ(results.size(), expected.size());
  same_as_precompute(0, inputs, results);
  Worst worst[kResultStride];
  for (std::size_t i = 0; i < cases.size(); ++i)
    for (int q = 0; q < kResultStride; ++q) {
      const double c = expected[i * kResultStride + q], v = results[i * kResultStride + q];
      double difference = std::abs(v - c) / std::max(1.0, std::abs(c));
      if ((q == kUvwzUNu || q == kUNu) && difference > tolerance) {
        // u_ν = acos((ν − μ μs) / √((1−μ²)(1−μs²))) / π has an infinite slope at
        // the ends of ν's range: one ulp of the argument below 1 moves it by
        // 4.7e-9. NVIDIA's fp64 (driver 580.159.04) lands there where C++ gives
        // exactly 0 or 1. Compared where it is well conditioned instead: the ν
        // each u_ν addresses at this μ, μs.
        const double nu_gpu = atmosphere::lut::scattering_nu_from_unit(cases[i].mu, cases[i].mu_s, v);
        const double nu_cpp = atmosphere::lut::scattering_nu_from_unit(cases[i].mu, cases[i].mu_s, c);
        difference = std::abs(nu_gpu - nu_cpp);
      }
      if (!fp64 && q == kRayHitsGround && std::abs(cases[i].mu - cases[i].horizon_mu) <= kFp32HorizonBand) continue;
      if (!(difference <= worst[q].difference)) worst[q] = {difference, describe(cases[i])};
      double bound = tolerance;
      if (q == kTransmittanceMu)
        bound = fp64 ? tolerance + transmittance_mu_bound(g, cases[i].r, cases[i].mu) : kFp32TopTolerance;
      EXPECT_LE(difference, bound) << kQuantities[q] << ": GPU " << v << ", C++ " << c << " at " << describe(cases[i]);
    }

  // Mode 1: scattering_texel_coordinates of every texel of the lowest and highest r layers.
  std::vector<double> texels;
  std::vector<double> texel_expected;
  for (AngleMapping mapping : {AngleMapping::Distance, AngleMapping::Blended})
    for (std::size_t z : {std::size_t{0}, s.scattering_r - 1})
      for (std::size_t y = 0; y < s.scattering_mu; ++y)
        for (std::size_t x = 0; x < s.scattering_width(); ++x) {
          texels.insert(texels.end(), {double(x), double(y), double(z), mapping == AngleMapping::Distance ? 0.0 : 1.0});
          texels.resize(texels.size() + (kCaseStride - 4), 0.0);
          const atmosphere::lut::ScatteringCoordinates c =
              atmosphere::lut::scattering_texel_coordinates(g, s, x, y, z, mapping);
          texel_expected.insert(texel_expected.end(), {c.r_m, c.mu, c.mu_s, c.nu, c.ray_hits_ground ? 1.0 : 0.0});
        }
  const std::vector<double> texel_results = gpu.run(1, texels);
  same_as_precompute(1, texels, texel_results);
  Worst texel_worst[5];
  const std::size_t texel_count = texels.size() / kCaseStride;
  for (std::size_t i = 0; i < texel_count; ++i)
    for (int q = 0; q < 5; ++q) {
      const double c = texel_expected[i * 5 + q], v = texel_results[i * kResultStride + q];
      double difference = std::abs(v - c) / std::max(1.0, std::abs(c));
      if (q == kTexelNu) {
        // ν = μ μs + √((1−μ²)(1−μs²)) cos(π x_ν) is ill conditioned at the
        // texels of μ = ±1 (the zenith row of the ground layer, the nadir row
        // of the top one): one ulp of μ below 1 there makes √(1−μ²) = 1.5e-8
        // instead of 0. NVIDIA's fp64 (driver 580.159.04, H100) lands μ one
        // ulp from C++'s there and ν 2.3e-8 from it (the texel μ itself
        // agrees within 4.4e-16). Compared where it is well conditioned
        // instead: ν from the GPU's own μ and μs by the C++ function.
        const std::size_t x = std::size_t(texels[i * kCaseStride]);
        const double x_nu = double(x / s.scattering_mu_s) / double(s.scattering_nu - 1);
        const double nu_cpp = atmosphere::lut::scattering_nu_from_unit(
            texel_results[i * kResultStride + kTexelMu], texel_results[i * kResultStride + kTexelMuS], x_nu);
        difference = std::abs(v - nu_cpp);
      }
      const std::string where = "texel (" + std::to_string(int(texels[i * kCaseStride])) + ", " +
                                std::to_string(int(texels[i * kCaseStride + 1])) + ", " +
                                std::to_string(int(texels[i * kCaseStride + 2])) + "), mapping " +
                                std::to_string(int(texels[i * kCaseStride + 3]));
      if (!(difference <= texel_worst[q].difference)) texel_worst[q] = {difference, where};
      EXPECT_LE(difference, tolerance) << kTexelQuantities[q] << ": GPU " << v << ", C++ " << c << " at " << where;
    }

  std::printf("%s %s%s: %zu cases, %zu texels; worst |GPU - C++| / max(1, |C++|):\n", preset.c_str(),
              fp64 ? "fp64" : "fp32", ulp_perturbation ? " (sqrt, exp, log perturbed)" : "", cases.size(), texel_count);
  for (int q = 0; q < kResultStride; ++q)
    std::printf("  %-26s %.3g  (%s)\n", kQuantities[q], worst[q].difference, worst[q].where.c_str());
  for (int q = 0; q < 5; ++q)
    std::printf("  %-26s %.3g  (%s)\n", kTexelQuantities[q], texel_worst[q].difference, texel_worst[q].where.c_str());
}

TEST(ParameterizationGpu, MatchesCppAtTheEdgesForEarthInFp64) {
  compare_parameterization("earth-advanced", true, kFp64Tolerance);
}
TEST(ParameterizationGpu, MatchesCppAtTheEdgesForMarsInFp64) { compare_parameterization("mars", true, kFp64Tolerance); }
TEST(ParameterizationGpu, MatchesCppAtTheEdgesForEarthInFp32) {
  compare_parameterization("earth-advanced", false, kFp32Tolerance);
}
TEST(ParameterizationGpu, MatchesCppAtTheEdgesForMarsInFp32) {
  compare_parameterization("mars", false, kFp32Tolerance);
}

// The render passes' programs, one for every atmosphere (the radii and the
// μs mapping's limit from WavelengthData's header): the C++ values as the
// precompute's programs, and those programs' own.
TEST(ParameterizationGpu, TheSharedRenderProgramIsThePrecomputesForEarthAndMarsInFp32) {
  compare_parameterization("earth-advanced", false, kFp32Tolerance, 0, true);
  compare_parameterization("mars", false, kFp32Tolerance, 0, true);
}
TEST(ParameterizationGpu, TheSharedRenderProgramIsThePrecomputesForEarthAndMarsInFp64) {
  compare_parameterization("earth-advanced", true, kFp64Tolerance, 0, true);
  compare_parameterization("mars", true, kFp64Tolerance, 0, true);
}

// NVIDIA's rounding on llvmpipe: sqrt, exp_r and log_r of double 1 ulp away from
// zero (tests/render/shader_faults.h), as NVIDIA's fp64 sqrt (driver
// 580.159.04) is.
TEST(ParameterizationGpu, MatchesCppAtTheEdgesForEarthInFp64WithSqrtOneUlpOff) {
  compare_parameterization("earth-advanced", true, kFp64Tolerance, 1);
}
TEST(ParameterizationGpu, MatchesCppAtTheEdgesForMarsInFp64WithSqrtOneUlpOff) {
  compare_parameterization("mars", true, kFp64Tolerance, 1);
}

}  // namespace
}  // namespace zenith::render
