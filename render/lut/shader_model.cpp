#include "render/lut/shader_model.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>

#include "atmosphere/lut/gauss_legendre.h"
#include "atmosphere/lut/lookup_tables.h"
#include "atmosphere/lut/parameterization.h"
#include "atmosphere/lut/quadrature.h"
#include "atmosphere/lut/spherical_harmonics.h"
#include "atmosphere/phase_functions.h"
#include "core/units.h"
#include "render/shader_bindings.h"

namespace zenith::render {

using atmosphere::AtmosphereModel;
using atmosphere::DensityProfile;
using atmosphere::MiePhase;
using atmosphere::RayleighPhaseModel;
using atmosphere::lut::PrecomputeOptions;
using atmosphere::lut::TableSizes;

namespace {

constexpr std::size_t kLanes = kWavelengthLanes;

// Per-group real4 fields of WavelengthData (FIELD_* in atmosphere_common.glsl).
enum WavelengthField : std::size_t {
  kRayleighScattering = 0,
  kMieScattering,
  kMieExtinction,
  kMieG1,
  kMieG2,
  kMieAlpha,
  kGroundAlbedo,
  kAbsorbers,  // absorber k: kAbsorbers + k
};

/// The constants of the double elementary functions (atmosphere/maths.glsl:
/// exp_r, log_r, sincos_r), fdlibm's: ln 2 split so that k·LN2_HI is exact
/// (LN2_HI its first 32 bits, LN2_LO the rest), 1/ln 2, 2/π, π/2 split the same
/// way (PIO2_1 its first 33 bits, PIO2_1T the rest), √½.
constexpr std::pair<const char*, double> kFp64MathsConstants[] = {
    {"LN2_HI", 6.93147180369123816490e-01},    {"LN2_LO", 1.90821492927058770002e-10},
    {"INV_LN2", 1.44269504088896338700e+00},   {"TWO_OVER_PI", 6.36619772367581382433e-01},
    {"PIO2_1", 1.57079632673412561417e+00},    {"PIO2_1T", 6.07710050650619224932e-11},
    {"SQRT_HALF", 7.07106781186547524401e-01},
};

/// The precompute's defines as the shared render programs take them
/// (ShaderModel::shared_defines): the model's own values from WavelengthData's
/// header, the precompute's alone dropped.
std::vector<gl::ShaderDefine> shared_render_defines(const std::vector<gl::ShaderDefine>& defines, bool fp64) {
  static const std::map<std::string, std::string> kAtRunTime = {
      {"BOTTOM_RADIUS", "wavelength_data[0].x"},           {"TOP_RADIUS", "wavelength_data[0].y"},
      {"RAYLEIGH_DEPOLARIZATION", "wavelength_data[0].z"}, {"WAVELENGTH_FIELDS", "int(wavelength_data[1].z)"},
      {"MIE_TABLE", "int(wavelength_data[2].y)"},
  };
  static const std::set<std::string> kPrecomputeOnly = {
      "RAYLEIGH_PHASE",         "MIE_PHASE",      "ABSORBER_COUNT",      "AIR_MASS",
      "AIR_MASS_GROUND_RADIUS", "AIR_MASS_TABLE", "AIR_MASS_TABLE_SIZE", "SPHERE_RULE",
      "HEMISPHERE_RULE",        "HARMONIC_RULE",  "RAYLEIGH_MOMENTS",    "MIE_MOMENTS"};
  std::vector<gl::ShaderDefine> out;
  for (const gl::ShaderDefine& d : defines) {
    if (kPrecomputeOnly.contains(d.name)) continue;
    if (const auto it = kAtRunTime.find(d.name); it != kAtRunTime.end()) {
      out.push_back({d.name, it->second});
    } else if (d.name == "WAVELENGTH_DATA_SIZE") {
      out.push_back(
          {d.name, std::to_string(kMaxWavelengthDataBytes / (kLanes * (fp64 ? sizeof(double) : sizeof(float))))});
    } else {
      out.push_back(d);
    }
  }
  out.push_back({"MODEL_AT_RUN_TIME", "1"});
  return out;
}

/// H = √(rt² − rb²) and the limit A of the μs distance mapping, with the
/// operations of horizon_distance_at_top() and distance_mapping_limit()
/// (parameterization.glsl, PRECISE: no fused multiply-add) in the shaders'
/// precision `Real`: a shared render program reads them from WavelengthData's
/// header and gets the bits the precompute's compiler folds from its literals.
template <typename Real>
std::pair<double, double> shell_constants(double bottom_radius_m, double top_radius_m) {
  const Real rb = static_cast<Real>(bottom_radius_m), rt = static_cast<Real>(top_radius_m);
  const auto safe_sqrt = [](Real a) { return std::sqrt(std::max(a, Real(0))); };
  const Real H = safe_sqrt((rt - rb) * (rt + rb));
  const Real s = H / rt;
  const Real mu_s_min = s >= Real(0.5) ? Real(-1) : -(Real(3) * s - Real(4) * s * s * s);
  const Real r_mu = rb * mu_s_min;
  const Real disc = r_mu * r_mu - (rb - rt) * (rb + rt);
  const Real distance = std::max(Real(0), -r_mu + safe_sqrt(disc));
  const Real d_min = rt - rb, d_max = H;
  const Real A = (distance - d_min) / (d_max - d_min);
  return {static_cast<double>(H), static_cast<double>(A)};
}

/// WavelengthData padded to kMaxWavelengthDataBytes: the shared render
/// programs declare the block at that size, and a buffer smaller than a block
/// leaves its reads undefined (GL 4.5, 7.6.3).
std::vector<double> wavelength_block(const ShaderModel& model) {
  std::vector<double> block = model.wavelength_data;
  block.resize(std::max(block.size(), kMaxWavelengthDataBytes / (model.fp64 ? sizeof(double) : sizeof(float))), 0.0);
  return block;
}

}  // namespace

TexelCoordinateLayout texel_coordinate_layout(const TableSizes& sizes) {
  TexelCoordinateLayout l;
  l.mu_s = 0;
  l.sun_theta_max = l.mu_s + 2 * sizes.scattering_mu_s;  // both angle mappings
  l.mu_sky = l.sun_theta_max + 1;
  l.count = l.mu_sky + 2 * sizes.scattering_r * (sizes.scattering_mu / 2);
  return l;
}

std::string glsl_literal(double v, bool fp64) {
  // 17 significant digits round-trip a double exactly; 9 a float.
  return fp64 ? fmt::format("{:.16e}LF", v) : fmt::format("{:.8e}", v);
}

gl::Buffer real_buffer(const std::vector<double>& values, bool fp64) {
  if (fp64) return gl::Buffer::from(std::span<const double>(values));
  std::vector<float> f(values.size());
  std::transform(values.begin(), values.end(), f.begin(), [](double v) { return static_cast<float>(v); });
  return gl::Buffer::from(std::span<const float>(f));
}

ModelBuffers::ModelBuffers(const ShaderModel& model)
    : wavelength_data(real_buffer(wavelength_block(model), model.fp64)),
      table_data(real_buffer(model.table_data, model.fp64)) {
  if (!model.fp64_constants.empty()) fp64_constants = gl::Buffer::from(std::span<const double>(model.fp64_constants));
}

void ModelBuffers::bind() const {
  wavelength_data.bind_uniform(binding::kWavelengthData);
  table_data.bind_storage(binding::kTableData);
  if (fp64_constants.id() != 0) fp64_constants.bind_uniform(binding::kFp64Constants);
}

ShaderModel shader_model(const AtmosphereModel& model, const PrecomputeOptions& options, bool fp64) {
  ShaderModel out;
  const std::size_t n = model.wavelength_count();
  out.group_count = (n + kLanes - 1) / kLanes;
  const std::size_t absorbers = model.absorbers.size();
  const std::size_t fields = kAbsorbers + absorbers;

  auto rayleigh_phase = [&] {
    switch (model.rayleigh_phase) {
      case RayleighPhaseModel::Classic: return 0;
      case RayleighPhaseModel::Penndorf: return 1;
      case RayleighPhaseModel::Depolarized: return 2;
    }
    return 1;
  };
  auto mie_phase = [&] {
    switch (model.mie_phase.model) {
      case MiePhase::Model::HenyeyGreenstein: return 0;
      case MiePhase::Model::DoubleHenyeyGreenstein: return 1;
      case MiePhase::Model::CornetteShanks: return 2;
      case MiePhase::Model::Tabulated: return 3;
    }
    return 0;
  };

  // The header the shared render programs read (ShaderModel::wavelength_data),
  // then the per-wavelength coefficients, 4 lanes per group; lanes past N stay zero.
  std::vector<double> wavelength_data((kModelHeaderVectors + out.group_count * fields) * kLanes, 0.0);
  const auto [horizon_distance_m, mapping_limit] =
      fp64 ? shell_constants<double>(model.ground_radius_m, model.top_radius_m)
           : shell_constants<float>(model.ground_radius_m, model.top_radius_m);
  const double header[kModelHeaderVectors * kLanes] = {model.ground_radius_m,
                                                       model.top_radius_m,
                                                       model.rayleigh_depolarization,
                                                       horizon_distance_m,  //
                                                       double(rayleigh_phase()),
                                                       double(mie_phase()),
                                                       double(fields),
                                                       model.has_mie() ? 1.0 : 0.0,  //
                                                       mapping_limit,
                                                       0.0,  // the Mie phase table's offset, set below
                                                       0.0,
                                                       0.0};
  std::copy(std::begin(header), std::end(header), wavelength_data.begin());
  auto put = [&](std::size_t field, const atmosphere::Spectrum& s) {
    for (std::size_t i = 0; i < n && i < s.size(); ++i)
      wavelength_data[(kModelHeaderVectors + (i / kLanes) * fields + field) * kLanes + i % kLanes] = s[i];
  };
  put(kRayleighScattering, model.rayleigh_scattering_m1);
  put(kMieScattering, model.mie_scattering_m1);
  put(kMieExtinction, model.mie_extinction_m1);
  put(kMieG1, model.mie_phase.g1);
  put(kMieG2, model.mie_phase.g2);
  put(kMieAlpha, model.mie_phase.alpha);
  put(kGroundAlbedo, model.ground_albedo);
  for (std::size_t a = 0; a < absorbers; ++a) put(kAbsorbers + a, model.absorbers[a].absorption_m1);

  // Profile descriptors first (4 reals each, absorbers contiguous), then knots and the air-mass table.
  std::vector<const DensityProfile*> profiles = {&model.rayleigh_density, &model.mie_density,
                                                 &model.air_mass.molecular_profile()};
  for (const auto& a : model.absorbers) profiles.push_back(&a.profile);
  std::vector<double> table(4 * profiles.size(), 0.0);
  for (std::size_t k = 0; k < profiles.size(); ++k) {
    const DensityProfile& p = *profiles[k];
    if (p.kind() == DensityProfile::Kind::Exponential) {
      table[4 * k] = 0.0;
      table[4 * k + 1] = p.scale_height_m();
      continue;
    }
    const auto& spline = p.table();
    table[4 * k] = 1.0;
    table[4 * k + 2] = static_cast<double>(table.size());
    table[4 * k + 3] = static_cast<double>(spline.knots_x().size());
    table.insert(table.end(), spline.knots_x().begin(), spline.knots_x().end());
    table.insert(table.end(), spline.knots_y().begin(), spline.knots_y().end());
    table.insert(table.end(), spline.slopes().begin(), spline.slopes().end());
  }
  // The direction quadratures of the scattering density (sphere) and sky irradiance
  // (hemisphere): the CPU's Gauss–Legendre rules, nodes then weights.
  const int sphere_nodes = options.sphere_zenith_samples, hemisphere_nodes = std::max(1, sphere_nodes / 2);
  const std::size_t sphere_rule = table.size();
  const atmosphere::lut::GaussLegendre sphere(sphere_nodes);
  table.insert(table.end(), sphere.nodes.begin(), sphere.nodes.end());
  table.insert(table.end(), sphere.weights.begin(), sphere.weights.end());
  const std::size_t hemisphere_rule = table.size();
  const atmosphere::lut::GaussLegendre hemisphere(hemisphere_nodes);
  table.insert(table.end(), hemisphere.nodes.begin(), hemisphere.nodes.end());
  table.insert(table.end(), hemisphere.weights.begin(), hemisphere.weights.end());

  // The harmonic scattering density (spherical_harmonics.h): per r layer of
  // the scattering table, its horizon-split rule (2·nodes μ, then 2·nodes
  // weights); the Legendre moments of the Rayleigh phase (degree + 1), then of
  // the Mie phase per wavelength (degree + 1 each, lanes past N zero).
  const int harmonic_degree = options.harmonic_degree_used();
  const std::size_t harmonic_rule = table.size();
  const atmosphere::lut::ShellGeometry shell{model.ground_radius_m, model.top_radius_m};
  for (std::size_t z = 0; z < options.sizes.scattering_r; ++z) {
    const double r = atmosphere::lut::scattering_texel_coordinates(shell, options.sizes, 0, 0, z,
                                                                   atmosphere::lut::AngleMapping::Blended)
                         .r_m;
    const atmosphere::lut::HorizonSplitRule rule(model.ground_radius_m, r, sphere_nodes);
    table.insert(table.end(), rule.mu.begin(), rule.mu.end());
    table.insert(table.end(), rule.weight.begin(), rule.weight.end());
  }
  const std::size_t rayleigh_moments = table.size();
  const std::vector<double> rayleigh = atmosphere::lut::phase_legendre_moments(
      [&](double x) { return model.rayleigh_phase_function(x); }, harmonic_degree);
  table.insert(table.end(), rayleigh.begin(), rayleigh.end());
  const std::size_t mie_moments = table.size();
  table.resize(table.size() + out.group_count * kLanes * static_cast<std::size_t>(harmonic_degree + 1), 0.0);
  if (model.has_mie())
    for (std::size_t i = 0; i < n; ++i) {
      const std::vector<double> mie =
          atmosphere::lut::phase_legendre_moments([&](double x) { return model.mie_phase(i, x); }, harmonic_degree);
      std::copy(mie.begin(), mie.end(), table.begin() + static_cast<std::ptrdiff_t>(mie_moments + i * mie.size()));
    }

  const bool air_mass = model.air_mass.enabled();
  const std::size_t air_mass_table = table.size();
  const std::size_t air_mass_size = air_mass ? model.air_mass.cos_zenith_table().size() : 0;
  if (air_mass) {
    table.insert(table.end(), model.air_mass.cos_zenith_table().begin(), model.air_mass.cos_zenith_table().end());
    table.insert(table.end(), model.air_mass.stretch_table().begin(), model.air_mass.stretch_table().end());
  }

  // A tabulated Mie phase: TabulatedPhase::kSamples per wavelength (lanes past N zero).
  const std::size_t mie_table = table.size();
  if (model.has_mie() && model.mie_phase.model == MiePhase::Model::Tabulated) {
    const std::vector<double>& samples = model.mie_phase.table->samples();
    table.resize(table.size() + out.group_count * kLanes * atmosphere::TabulatedPhase::kSamples, 0.0);
    std::copy(samples.begin(), samples.end(), table.begin() + static_cast<std::ptrdiff_t>(mie_table));
  }
  wavelength_data[2 * kLanes + 1] = double(mie_table);

  // WavelengthData is a uniform block: GL guarantees 16 KiB of one (GL_MAX_UNIFORM_BLOCK_SIZE).
  const std::size_t block_bytes = wavelength_data.size() * (fp64 ? sizeof(double) : sizeof(float));
  if (block_bytes > kMaxWavelengthDataBytes)
    throw std::invalid_argument(fmt::format(
        "atmosphere '{}': {} wavelengths with {} absorbers need {} bytes of model parameters per shader, more than "
        "the {} a GL uniform block is guaranteed to hold; use fewer wavelengths or absorbers",
        model.name, n, absorbers, block_bytes, kMaxWavelengthDataBytes));
  out.wavelength_data = std::move(wavelength_data);
  out.table_data = std::move(table);

  const TableSizes& s = options.sizes;
  auto define = [&](const char* name, const auto& value) { out.defines.push_back({name, fmt::format("{}", value)}); };
  define("USE_FP64", fp64 ? 1 : 0);
  out.fp64 = fp64;
  // A real constant: a float literal in fp32; in fp64 the next entry of the
  // Fp64Constants uniform block (atmosphere/maths.glsl), the define naming it,
  // so the shader gets the C++ double's bits, never a literal a driver parses.
  auto real_constant = [&](const char* name, double value) {
    if (!fp64) {
      out.defines.push_back({name, glsl_literal(value, false)});
      return;
    }
    const std::size_t i = out.fp64_constants.size();
    out.fp64_constants.push_back(value);
    out.defines.push_back({name, fmt::format("fp64_constants[{}].{}", i / 4, "xyzw"[i % 4])});
  };
  if (fp64)
    for (const auto& [name, value] : kFp64MathsConstants) real_constant(name, value);
  real_constant("BOTTOM_RADIUS", model.ground_radius_m);
  real_constant("TOP_RADIUS", model.top_radius_m);
  define("TRANSMITTANCE_MU", s.transmittance_mu);
  define("TRANSMITTANCE_R", s.transmittance_r);
  define("IRRADIANCE_MU_S", s.irradiance_mu_s);
  define("IRRADIANCE_R", s.irradiance_r);
  define("SCATTERING_R", s.scattering_r);
  define("SCATTERING_MU", s.scattering_mu);
  define("SCATTERING_MU_S", s.scattering_mu_s);
  define("SCATTERING_NU", s.scattering_nu);
  real_constant("NU_SPREAD_MIN", atmosphere::lut::kNuSpreadMin);
  define("GEOMETRIC_BLEND_FULL_LOG_RATIO", glsl_literal(double(atmosphere::lut::kGeometricBlendFullLogRatio), false));
  // Constants shared with the CPU code, from their C++ definitions.
  real_constant("PI", core::kPi);
  real_constant("INV_4PI", atmosphere::kInv4Pi);
  real_constant("PENNDORF_A", atmosphere::kPenndorfA);
  real_constant("PENNDORF_B", atmosphere::kPenndorfB);
  real_constant("SERIES_LIMIT", atmosphere::lut::kLogLinearSeriesLimit);
  define("FIELD_RAYLEIGH_SCATTERING", std::size_t{kRayleighScattering});
  define("FIELD_MIE_SCATTERING", std::size_t{kMieScattering});
  define("FIELD_MIE_EXTINCTION", std::size_t{kMieExtinction});
  define("FIELD_MIE_G1", std::size_t{kMieG1});
  define("FIELD_MIE_G2", std::size_t{kMieG2});
  define("FIELD_MIE_ALPHA", std::size_t{kMieAlpha});
  define("FIELD_GROUND_ALBEDO", std::size_t{kGroundAlbedo});
  define("FIELD_ABSORBERS", std::size_t{kAbsorbers});
  out.texel_layout = texel_coordinate_layout(s);
  define("TEXEL_MU_S", out.texel_layout.mu_s);
  define("TEXEL_SUN_THETA_MAX", out.texel_layout.sun_theta_max);
  define("TEXEL_MU_SKY", out.texel_layout.mu_sky);
  define("TEXEL_VALUE_COUNT", out.texel_layout.count);
  define("RAYLEIGH_PHASE", rayleigh_phase());
  real_constant("RAYLEIGH_DEPOLARIZATION", model.rayleigh_depolarization);
  define("HAS_MIE", model.has_mie() ? 1 : 0);
  define("MIE_PHASE", mie_phase());
  define("ABSORBER_COUNT", absorbers);
  define("MODEL_HEADER_VECTORS", kModelHeaderVectors);
  define("WAVELENGTH_FIELDS", fields);
  define("WAVELENGTH_DATA_SIZE", kModelHeaderVectors + out.group_count * fields);
  define("RAYLEIGH_PROFILE", 0);
  define("MIE_PROFILE", 4);
  define("AIR_MASS_PROFILE", 8);
  define("ABSORBER_PROFILES", 12);
  define("AIR_MASS", air_mass ? 1 : 0);
  real_constant("AIR_MASS_GROUND_RADIUS", model.air_mass.ground_radius_m());
  define("AIR_MASS_TABLE", air_mass_table);
  define("AIR_MASS_TABLE_SIZE", air_mass_size);
  define("QUADRATURE_LOG_LINEAR", options.scattering_quadrature == PrecomputeOptions::Quadrature::LogLinear ? 1 : 0);
  define("SCATTERING_SAMPLES", options.scattering_samples);
  define("OPTICAL_DEPTH_SUBSTEPS", atmosphere::lut::kOpticalDepthSubsteps);
  define("TRANSMITTANCE_SAMPLES", options.transmittance_samples + options.transmittance_samples % 2);
  define("SPHERE_ZENITH_SAMPLES", sphere_nodes);
  define("HEMISPHERE_ZENITH_SAMPLES", hemisphere_nodes);
  define("SPHERE_RULE", sphere_rule);
  define("HEMISPHERE_RULE", hemisphere_rule);
  define("HARMONIC_DEGREE", harmonic_degree);
  define("HARMONIC_RULE", harmonic_rule);
  define("RAYLEIGH_MOMENTS", rayleigh_moments);
  define("MIE_MOMENTS", mie_moments);
  define("MIE_TABLE", mie_table);
  define("MIE_TABLE_SAMPLES", atmosphere::TabulatedPhase::kSamples);
  if (fp64) {
    define("FP64_CONSTANT_VECTORS", (out.fp64_constants.size() + 3) / 4);
    out.fp64_constants.resize((out.fp64_constants.size() + 3) / 4 * 4, 0.0);  // whole dvec4s (std140)
  }
  out.shared_defines = shared_render_defines(out.defines, fp64);
  define("MODEL_AT_RUN_TIME", 0);
  return out;
}

}  // namespace zenith::render
