#include "render/lut/gpu_precompute.h"

#include <epoxy/gl.h>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "atmosphere/lut/series_tail.h"
#include "atmosphere/lut/spherical_harmonics.h"
#include "atmosphere/model_hash.h"
#include "render/gl/buffer.h"
#include "render/gl/first_dispatch_warmup.h"
#include "render/gl/gl_error.h"
#include "render/gl/gl_limits.h"
#include "render/gl/program_binary_cache.h"
#include "render/gl/program_builds.h"
#include "render/gl/shader_program.h"
#include "render/gl/texture.h"
#include "render/lut/shader_model.h"
#include "render/shader_bindings.h"
#include "render/shader_programs.h"

namespace zenith::render {

const char* to_string(GpuPrecision precision) {
  switch (precision) {
    case GpuPrecision::automatic: return "auto";
    case GpuPrecision::fp64: return "fp64";
    case GpuPrecision::fp32: return "fp32";
  }
  return "?";
}

namespace {

using atmosphere::AtmosphereModel;
using atmosphere::lut::LookupTables;
using atmosphere::lut::PrecomputeOptions;
using atmosphere::lut::PrecomputeReport;
using atmosphere::lut::Table2D;
using atmosphere::lut::Table3D;
using atmosphere::lut::TableSizes;
using gl::ShaderDefine;
using gl::ShaderProgram;
using gl::Texture;
using gl::TextureFormat;

constexpr std::size_t kLanes = kWavelengthLanes;

// Binding points shared with the shaders: render/shader_bindings.h.
using namespace binding;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

int to_int(std::size_t v) { return static_cast<int>(v); }

/// One group of 4 wavelengths' tables on the GPU (RGBA32F, created when first needed).
struct GroupTables {
  Texture transmittance, irradiance, delta_irradiance;
  Texture single_rayleigh, single_mie, multiple, delta_radiance, density;
  /// The deltas of the order before the last, for the series tail (only with it).
  Texture previous_delta_irradiance, previous_delta_radiance;
};

class GpuPrecompute {
 public:
  GpuPrecompute(const AtmosphereModel& model, const PrecomputeOptions& options, PrecomputeReport* report,
                const gl::HeadlessContext& context, bool fp64, gl::ProgramBinaryCache* binaries,
                gl::CompileMode compile);
  LookupTables run();
  const gl::ProgramBuilds& builds() const { return builds_; }

 private:
  const TableSizes& sizes() const { return options_.sizes; }
  std::size_t group_count() const { return groups_.size(); }
  /// TEXEL_VALUE_COUNT: μs per mapping, acos(μs_min), sky μ per mapping and r.
  std::size_t texel_coordinate_count() const { return texel_layout_.count; }
  void prepare_model_data();
  void check_limits() const;
  /// Every program that run() will use, with the extra defines of its
  /// variant: their builds start together at the beginning (ProgramBuilds).
  std::vector<std::pair<std::string, std::vector<ShaderDefine>>> needed_programs() const;
  void start_programs();
  /// CompileMode::contexts: up to `programs` threads with a context each, the builds' (ProgramBuilds::build_on).
  void start_compile_threads(std::size_t programs);
  static std::string program_key(const std::string& file, const std::vector<ShaderDefine>& extra);
  gl::ProgramBuilds::Starter program_starter(const std::string& file, const std::vector<ShaderDefine>& extra) const;
  /// The program of `file` with `extra` defines: its build (started by
  /// start_programs, or now) finished where first used.
  const ShaderProgram& program(const std::string& file, const std::vector<ShaderDefine>& extra = {});
  void stage(const std::string& name, double fraction, auto&& body);
  void dispatch_scattering(const ShaderProgram& p) const;
  /// T(x, y_i) and (u_r, u_μ) at the samples of every view ray of the scattering
  /// table for wavelength group g and the stage's μ mapping (view_transmittance.comp),
  /// bound to kViewTransmittance and kViewRayCoordinates for the stage's shader.
  void compute_view_transmittance(std::size_t group, bool distance_mapping);
  static void barrier() { glMemoryBarrier(GL_ALL_BARRIER_BITS); }
  Texture new_scattering_texture() const;
  static void unpack(const Texture& texture, std::size_t group, std::size_t channels, std::vector<float>& out);

  void compute_transmittance();
  void compute_single_scattering();
  void bind_previous_order_radiance(GroupTables& t, int order) const;
  void compute_scattering_density(int order);
  /// DensityMethod::Harmonics: radiance_harmonics, harmonic_projection, harmonic_density.comp.
  void compute_scattering_density_harmonics(int order);
  /// DensityMethod::Direct: scattering_density.comp.
  void compute_scattering_density_direct(int order);
  void compute_indirect_irradiance(int order);
  double compute_multiple_scattering(int sample_stride);
  /// Σ over texels and wavelengths: single scattering with phases, or the last
  /// order's radiance; each wavelength's Σ is left in channel_sums_.
  double radiance_sum(bool single);
  /// The series tail of every group's radiance (series_tail.comp) and
  /// irradiance, and the readback of the final tables; returns Σ of the radiance's tail.
  double add_series_tail();
  void read_back_multiple_orders();

  const AtmosphereModel& model_;
  const PrecomputeOptions& options_;
  PrecomputeReport* report_;
  const gl::HeadlessContext& context_;
  const bool fp64_;
  std::size_t n_;
  LookupTables tables_;
  std::vector<ShaderDefine> defines_;
  TexelCoordinateLayout texel_layout_;
  ModelBuffers model_buffers_;  // WavelengthData, TableData, Fp64Constants (render/lut/shader_model.h)
  gl::Buffer texel_coordinates_, row_sums_;
  gl::Buffer azimuth_moments_, harmonic_coefficients_;  // DensityMethod::Harmonics, one group at a time
  gl::Buffer view_transmittance_, view_ray_uv_;         // view_ray.glsl, one group at a time
  std::vector<GroupTables> groups_;
  gl::ProgramBinaryCache* binaries_;  ///< null: every program compiled
  gl::ProgramBuilds builds_;
  std::unique_ptr<gl::FirstDispatchWarmup> warmup_;  // after builds_: stops before the programs go
  /// CompileMode::contexts: a thread and context per program, building (after builds_, as warmup_).
  std::vector<std::unique_ptr<gl::FirstDispatchWarmup>> compile_threads_;
  double fraction_done_ = 0.0;
  /// Σ over the table of each wavelength's radiance in the last radiance_sum,
  /// and in the one before that of the last order (the series tail's caps).
  std::vector<double> channel_sums_, previous_channel_sums_;
};

GpuPrecompute::GpuPrecompute(const AtmosphereModel& model, const PrecomputeOptions& options, PrecomputeReport* report,
                             const gl::HeadlessContext& context, bool fp64, gl::ProgramBinaryCache* binaries,
                             gl::CompileMode compile)
    : model_(model),
      options_(options),
      report_(report),
      context_(context),
      fp64_(fp64),
      n_(model.wavelength_count()),
      tables_(LookupTables::allocate({model.ground_radius_m, model.top_radius_m}, options.sizes, n_)),
      binaries_(binaries),
      builds_(compile) {
  if (n_ > atmosphere::lut::kMaxChannels) throw std::invalid_argument("too many wavelengths for the lookup tables");
  if (n_ == 0) throw std::invalid_argument("the atmosphere has no wavelengths");
  atmosphere::lut::check_precompute_options(options);
  groups_.resize((n_ + kLanes - 1) / kLanes);
  check_limits();
  prepare_model_data();
}

void GpuPrecompute::check_limits() const {
  const gl::GlLimits limits = gl::query_gl_limits();
  const TableSizes& s = sizes();
  auto check = [](std::size_t v, int limit, const char* what) {
    if (v > static_cast<std::size_t>(limit))
      throw std::runtime_error(
          fmt::format("GPU precompute: {} = {} exceeds this GL implementation's limit {}", what, v, limit));
  };
  check(s.transmittance_mu, limits.max_texture_size, "transmittance_mu");
  check(s.transmittance_r, limits.max_texture_size, "transmittance_r");
  check(s.irradiance_mu_s, limits.max_texture_size, "irradiance_mu_s");
  check(s.irradiance_r, limits.max_texture_size, "irradiance_r");
  check(s.scattering_width(), limits.max_3d_texture_size, "scattering_nu * scattering_mu_s (3D texture width)");
  check(s.scattering_mu, limits.max_3d_texture_size, "scattering_mu");
  check(s.scattering_r, limits.max_3d_texture_size, "scattering_r");
}

void GpuPrecompute::prepare_model_data() {
  ShaderModel m = shader_model(model_, options_, fp64_);
  defines_ = std::move(m.defines);
  texel_layout_ = m.texel_layout;
  model_buffers_ = ModelBuffers(m);
  const std::size_t real_size = fp64_ ? sizeof(double) : sizeof(float);
  texel_coordinates_ = gl::Buffer(texel_coordinate_count() * real_size);
  row_sums_ = gl::Buffer(group_count() * sizes().scattering_r * sizes().scattering_mu * kLanes * real_size);
}

std::vector<std::pair<std::string, std::vector<ShaderDefine>>> GpuPrecompute::needed_programs() const {
  std::vector<std::pair<std::string, std::vector<ShaderDefine>>> out;
  auto need = [&](std::string file, std::vector<ShaderDefine> extra = {}) {
    out.emplace_back(std::move(file), std::move(extra));
  };
  const int orders = options_.max_orders;
  // The switches between orders are #defines, not uniforms: a uniform in a
  // branch costs llvmpipe a new variant at each of its values, in every run
  // (docs/gpu-precompute.md, "Parallel compilation").
  auto first_order = [&](const std::string& file) {
    need(file, {{"FIRST_ORDER", "1"}});
    if (orders > 2) need(file, {{"FIRST_ORDER", "0"}});
  };
  // In the order run() uses them, so that the first ones are ready first.
  need("transmittance.comp");
  need("texel_coordinates.comp");
  need("view_transmittance.comp", {{"VIEW_MAPPING", "ANGLE_MAPPING_DISTANCE"}});
  need("single_scattering.comp");
  need("radiance_sum.comp", {{"SINGLE", "1"}});
  if (orders < 2) return out;
  if (options_.density_method == PrecomputeOptions::DensityMethod::Harmonics) {
    first_order("radiance_harmonics.comp");
    need("harmonic_projection.comp");
    need("harmonic_density.comp");
  } else {
    first_order("scattering_density.comp");
  }
  first_order("indirect_irradiance.comp");
  need("view_transmittance.comp", {{"VIEW_MAPPING", "ANGLE_MAPPING_BLENDED"}});
  need("multiple_scattering.comp");
  need("radiance_sum.comp", {{"SINGLE", "0"}});
  // The tail follows from the third order on (run(): tail_follows); a
  // tolerance may stop before it, and then its build is abandoned.
  if (options_.series_tail && orders >= 3) need("series_tail.comp");
  return out;
}

void GpuPrecompute::start_programs() {
  const auto programs = needed_programs();
  if (builds_.mode() == gl::CompileMode::contexts) start_compile_threads(programs.size());
  for (const auto& [file, extra] : programs) builds_.start(program_key(file, extra), program_starter(file, extra));
  // llvmpipe: the later stages' machine code generated on a second thread
  // while the first stages run (render/gl/first_dispatch_warmup.h). Every
  // table here is rgba32f, one level, linear, clamped, with power-of-two sides
  // (TableSizes): the stand-ins' shape when none is given.
  if (builds_.mode() == gl::CompileMode::serial) return;
  warmup_ = gl::FirstDispatchWarmup::if_worthwhile("precompute");
  if (warmup_)
    builds_.warm_started(*warmup_, {}, [](const ShaderProgram&) { return 0; });  // needed_programs(): in stage order
}

void GpuPrecompute::start_compile_threads(std::size_t programs) {
  // As many as the programs, up to the cores: NVIDIA's compile of the slowest
  // programs takes a second each, and its own compiler threads overlap little
  // (docs/gpu-precompute.md, "On an NVIDIA H200").
  const std::size_t wanted = std::min<std::size_t>(programs, std::max(1u, std::thread::hardware_concurrency()));
  while (compile_threads_.size() < wanted) {
    try {
      compile_threads_.push_back(std::make_unique<gl::FirstDispatchWarmup>());
    } catch (const std::runtime_error& e) {  // EGL gave no more contexts: the builds share those made
      spdlog::info("GPU precompute: {} compile context{} of {} ({})", compile_threads_.size(),
                   compile_threads_.size() == 1 ? "" : "s", wanted, e.what());
      break;
    }
  }
  std::vector<gl::FirstDispatchWarmup*> threads;
  for (const auto& thread : compile_threads_) threads.push_back(thread.get());
  builds_.build_on(std::move(threads));
}

std::string GpuPrecompute::program_key(const std::string& file, const std::vector<ShaderDefine>& extra) {
  std::string key = file;
  for (const ShaderDefine& d : extra) key += fmt::format(" {}={}", d.name, d.value);
  return key;
}

gl::ProgramBuilds::Starter GpuPrecompute::program_starter(const std::string& file,
                                                          const std::vector<ShaderDefine>& extra) const {
  std::vector<ShaderDefine> defines = defines_;
  defines.insert(defines.end(), extra.begin(), extra.end());
  return [file, defines = std::move(defines), binaries = binaries_] {
    return start_compute_program(file, defines, binaries);
  };
}

const ShaderProgram& GpuPrecompute::program(const std::string& file, const std::vector<ShaderDefine>& extra) {
  return builds_.get(program_key(file, extra), program_starter(file, extra));
}

void GpuPrecompute::stage(const std::string& name, double fraction, auto&& body) {
  // As run_stage in cpu_precompute.cpp; glFinish so the time is the GPU's.
  if (options_.progress) options_.progress({name, fraction_done_});
  const auto start = std::chrono::steady_clock::now();
  body();
  glFinish();
  gl::check_gl_error(fmt::format("GPU precompute, stage '{}'", name));
  if (report_) report_->stages.push_back({name, seconds_since(start)});
  fraction_done_ += fraction;
  if (options_.progress) options_.progress({name, std::min(fraction_done_, 1.0)});
}

void GpuPrecompute::dispatch_scattering(const ShaderProgram& p) const {
  // One r layer per dispatch: no single dispatch runs long enough to trip a
  // display watchdog on a slow GPU at large table sizes.
  for (std::size_t z = 0; z < sizes().scattering_r; ++z) {
    p.set_uniform("z_offset", to_int(z));
    p.dispatch_covering(to_int(sizes().scattering_width()), to_int(sizes().scattering_mu), 1);
  }
}

void GpuPrecompute::compute_view_transmittance(std::size_t group, bool distance_mapping) {
  const std::size_t rays = sizes().scattering_r * sizes().scattering_mu;
  const std::size_t real4_size = 4 * (fp64_ ? sizeof(double) : sizeof(float));
  const std::size_t samples = rays * (static_cast<std::size_t>(options_.scattering_samples) + 1);
  if (view_transmittance_.id() == 0) {
    view_transmittance_ = gl::Buffer(samples * real4_size);
    view_ray_uv_ = gl::Buffer(samples * real4_size / 2);
  }
  const ShaderProgram& p =
      program("view_transmittance.comp",
              {{"VIEW_MAPPING", distance_mapping ? "ANGLE_MAPPING_DISTANCE" : "ANGLE_MAPPING_BLENDED"}});
  view_transmittance_.bind_storage(kViewTransmittance);
  view_ray_uv_.bind_storage(kViewRayCoordinates);
  p.set_uniform("wavelength_group", to_int(group));
  p.dispatch_covering(to_int(rays));
  barrier();
}

Texture GpuPrecompute::new_scattering_texture() const {
  return Texture::create_3d(TextureFormat::rgba32f, to_int(sizes().scattering_width()), to_int(sizes().scattering_mu),
                            to_int(sizes().scattering_r));
}

void GpuPrecompute::unpack(const Texture& texture, std::size_t group, std::size_t channels, std::vector<float>& out) {
  const std::vector<float> rgba = texture.read();
  const std::size_t texels = rgba.size() / kLanes, first = group * kLanes;
  const std::size_t lanes = std::min(kLanes, channels - first);
  for (std::size_t t = 0; t < texels; ++t)
    for (std::size_t k = 0; k < lanes; ++k) out[t * channels + first + k] = rgba[t * kLanes + k];
}

// ---------------------------------------------------------------- stages

void GpuPrecompute::compute_transmittance() {
  const TableSizes& s = sizes();
  const ShaderProgram& p = program("transmittance.comp");
  for (std::size_t g = 0; g < group_count(); ++g) {
    groups_[g].transmittance =
        Texture::create_2d(TextureFormat::rgba32f, to_int(s.transmittance_mu), to_int(s.transmittance_r));
    groups_[g].transmittance.bind_image(kOutputImage, gl::ImageAccess::write_only);
    p.set_uniform("wavelength_group", to_int(g));
    p.dispatch_covering(to_int(s.transmittance_mu), to_int(s.transmittance_r));
  }
  barrier();
  for (std::size_t g = 0; g < group_count(); ++g) unpack(groups_[g].transmittance, g, n_, tables_.transmittance.data);
}

void GpuPrecompute::compute_single_scattering() {
  // The texel coordinates the CPU finds by bisection, once (texel_coordinates.comp);
  // every scattering stage reads them.
  program("texel_coordinates.comp").dispatch_covering(to_int(texel_coordinate_count()));
  barrier();

  const ShaderProgram& p = program("single_scattering.comp");
  for (std::size_t g = 0; g < group_count(); ++g) {
    GroupTables& t = groups_[g];
    t.single_rayleigh = new_scattering_texture();
    t.single_rayleigh.bind_image(kOutputImage, gl::ImageAccess::write_only);
    if (model_.has_mie()) {
      t.single_mie = new_scattering_texture();
      t.single_mie.bind_image(kSecondOutputImage, gl::ImageAccess::write_only);
    }
    t.transmittance.bind(kTransmittanceUnit);
    compute_view_transmittance(g, true);
    p.set_uniform("wavelength_group", to_int(g));
    dispatch_scattering(p);
    barrier();  // before the next group's view transmittance overwrites this one's
  }
  for (std::size_t g = 0; g < group_count(); ++g) {
    unpack(groups_[g].single_rayleigh, g, n_, tables_.single_rayleigh.data);
    if (model_.has_mie()) unpack(groups_[g].single_mie, g, n_, tables_.single_mie.data);
  }
}

/// The radiance of order n−1 that orders n read: the single-scattering tables
/// (order 2) or the last order's delta table.
void GpuPrecompute::bind_previous_order_radiance(GroupTables& t, int order) const {
  if (order == 2) {
    t.single_rayleigh.bind(kSingleRayleighUnit);
    if (model_.has_mie()) t.single_mie.bind(kSingleMieUnit);
  } else {
    t.delta_radiance.bind(kDeltaRadianceUnit);
  }
}

void GpuPrecompute::compute_scattering_density(int order) {
  if (options_.density_method == PrecomputeOptions::DensityMethod::Harmonics)
    compute_scattering_density_harmonics(order);
  else
    compute_scattering_density_direct(order);
}

void GpuPrecompute::compute_scattering_density_harmonics(int order) {
  const TableSizes& s = sizes();
  const std::size_t columns = s.scattering_r * s.scattering_mu_s;
  const std::size_t nodes = 2 * static_cast<std::size_t>(options_.sphere_zenith_samples);
  const auto degree = static_cast<std::size_t>(options_.harmonic_degree_used());
  const std::size_t real4_size = 4 * (fp64_ ? sizeof(double) : sizeof(float));
  if (azimuth_moments_.id() == 0) {
    azimuth_moments_ = gl::Buffer(columns * nodes * (degree + 1) * real4_size);
    harmonic_coefficients_ = gl::Buffer(columns * atmosphere::lut::harmonic_count(int(degree)) * real4_size);
  }
  azimuth_moments_.bind_storage(kAzimuthMoments);
  harmonic_coefficients_.bind_storage(kHarmonicCoefficients);
  const ShaderProgram& radiance = program("radiance_harmonics.comp", {{"FIRST_ORDER", order == 2 ? "1" : "0"}});
  const ShaderProgram& projection = program("harmonic_projection.comp");
  const ShaderProgram& density = program("harmonic_density.comp");
  for (std::size_t g = 0; g < group_count(); ++g) {
    GroupTables& t = groups_[g];
    if (t.density.id() == 0) t.density = new_scattering_texture();
    t.transmittance.bind(kTransmittanceUnit);
    bind_previous_order_radiance(t, order);
    if (order > 2) t.delta_irradiance.bind(kDeltaIrradianceUnit);
    radiance.set_uniform("wavelength_group", to_int(g));
    radiance.dispatch_covering(to_int(columns * nodes));
    barrier();
    projection.set_uniform("wavelength_group", to_int(g));
    projection.dispatch_covering(to_int(columns * (degree + 1)));
    barrier();
    t.density.bind_image(kOutputImage, gl::ImageAccess::write_only);
    density.set_uniform("wavelength_group", to_int(g));
    density.dispatch_covering(to_int(columns * s.scattering_mu));
    barrier();
  }
}

void GpuPrecompute::compute_scattering_density_direct(int order) {
  const ShaderProgram& p = program("scattering_density.comp", {{"FIRST_ORDER", order == 2 ? "1" : "0"}});
  for (std::size_t g = 0; g < group_count(); ++g) {
    GroupTables& t = groups_[g];
    if (t.density.id() == 0) t.density = new_scattering_texture();
    t.density.bind_image(kOutputImage, gl::ImageAccess::write_only);
    t.transmittance.bind(kTransmittanceUnit);
    bind_previous_order_radiance(t, order);
    if (order > 2) t.delta_irradiance.bind(kDeltaIrradianceUnit);
    p.set_uniform("wavelength_group", to_int(g));
    dispatch_scattering(p);
  }
  barrier();
}

void GpuPrecompute::compute_indirect_irradiance(int order) {
  const TableSizes& s = sizes();
  const ShaderProgram& p = program("indirect_irradiance.comp", {{"FIRST_ORDER", order == 2 ? "1" : "0"}});
  for (std::size_t g = 0; g < group_count(); ++g) {
    GroupTables& t = groups_[g];
    if (t.irradiance.id() == 0) {
      t.irradiance = Texture::create_2d(TextureFormat::rgba32f, to_int(s.irradiance_mu_s), to_int(s.irradiance_r));
      t.delta_irradiance =
          Texture::create_2d(TextureFormat::rgba32f, to_int(s.irradiance_mu_s), to_int(s.irradiance_r));
    }
    if (options_.series_tail) {  // keep the order before for the tail
      std::swap(t.delta_irradiance, t.previous_delta_irradiance);
      if (t.delta_irradiance.id() == 0)
        t.delta_irradiance =
            Texture::create_2d(TextureFormat::rgba32f, to_int(s.irradiance_mu_s), to_int(s.irradiance_r));
    }
    t.delta_irradiance.bind_image(kOutputImage, gl::ImageAccess::write_only);
    t.irradiance.bind_image(kSecondOutputImage, gl::ImageAccess::read_write);
    t.transmittance.bind(kTransmittanceUnit);
    bind_previous_order_radiance(t, order);
    p.set_uniform("wavelength_group", to_int(g));
    p.dispatch_covering(to_int(s.irradiance_mu_s), to_int(s.irradiance_r));
  }
  barrier();
}

double GpuPrecompute::compute_multiple_scattering(int sample_stride) {
  const ShaderProgram& p = program("multiple_scattering.comp");
  for (std::size_t g = 0; g < group_count(); ++g) {
    GroupTables& t = groups_[g];
    if (t.multiple.id() == 0) {
      t.multiple = new_scattering_texture();
      t.delta_radiance = new_scattering_texture();
    }
    if (options_.series_tail) {  // keep the order before for the tail
      std::swap(t.delta_radiance, t.previous_delta_radiance);
      if (t.delta_radiance.id() == 0) t.delta_radiance = new_scattering_texture();
    }
    t.delta_radiance.bind_image(kOutputImage, gl::ImageAccess::write_only);
    t.multiple.bind_image(kSecondOutputImage, gl::ImageAccess::read_write);
    t.transmittance.bind(kTransmittanceUnit);
    t.density.bind(kDensityUnit);
    compute_view_transmittance(g, false);
    p.set_uniform("wavelength_group", to_int(g));
    p.set_uniform("sample_stride", sample_stride);
    dispatch_scattering(p);
    barrier();  // before the next group's view transmittance overwrites this one's
  }
  previous_channel_sums_ = std::move(channel_sums_);
  return radiance_sum(false);
}

double GpuPrecompute::radiance_sum(bool single) {
  const ShaderProgram& p = program("radiance_sum.comp", {{"SINGLE", single ? "1" : "0"}});
  const std::size_t rows = sizes().scattering_r * sizes().scattering_mu;
  for (std::size_t g = 0; g < group_count(); ++g) {
    GroupTables& t = groups_[g];
    if (single) {
      t.single_rayleigh.bind(kSingleRayleighUnit);
      if (model_.has_mie()) t.single_mie.bind(kSingleMieUnit);
    } else {
      t.delta_radiance.bind(kDeltaRadianceUnit);
    }
    p.set_uniform("wavelength_group", to_int(g));
    p.set_uniform("lanes", to_int(std::min(kLanes, n_ - g * kLanes)));
    p.dispatch_covering(to_int(rows));
  }
  barrier();
  // row_sums[(group · rows + row) · 4 + lane]: wavelength group · 4 + lane.
  std::vector<double> per_channel(n_, 0.0);
  auto add = [&](std::size_t i, double v) {
    const std::size_t channel = (i / (rows * kLanes)) * kLanes + i % kLanes;
    if (channel < n_) per_channel[channel] += v;
  };
  if (fp64_) {
    const std::vector<double> sums = row_sums_.read<double>();
    for (std::size_t i = 0; i < sums.size(); ++i) add(i, sums[i]);
  } else {
    const std::vector<float> sums = row_sums_.read<float>();
    for (std::size_t i = 0; i < sums.size(); ++i) add(i, static_cast<double>(sums[i]));
  }
  channel_sums_ = per_channel;
  double total = 0.0;
  for (double v : per_channel) total += v;
  return total;
}

double GpuPrecompute::add_series_tail() {
  // The radiance on the GPU, each wavelength's texel ratios capped from its
  // sums over the table (radiance_sum of the last two orders).
  const ShaderProgram& p = program("series_tail.comp");
  for (std::size_t g = 0; g < group_count(); ++g) {
    GroupTables& t = groups_[g];
    std::array<float, 4> cap{};
    for (std::size_t k = 0; k < kLanes && g * kLanes + k < n_; ++k) {
      const std::size_t c = g * kLanes + k;
      cap[k] = static_cast<float>(atmosphere::lut::series_tail_ratio_cap(channel_sums_[c], previous_channel_sums_[c]));
    }
    t.delta_radiance.bind_image(kOutputImage, gl::ImageAccess::read_write);
    t.multiple.bind_image(kSecondOutputImage, gl::ImageAccess::read_write);
    t.previous_delta_radiance.bind(kDeltaRadianceUnit);
    p.set_uniform("wavelength_group", to_int(g));
    p.set_uniform("ratio_cap", cap);
    dispatch_scattering(p);
  }
  barrier();
  const double tail_sum = radiance_sum(false);  // the deltas now hold the tail
  read_back_multiple_orders();
  // The irradiance (64×16 texels) on the CPU, with the CPU precompute's code.
  const TableSizes& s = sizes();
  Table2D last(s.irradiance_mu_s, s.irradiance_r, n_), before(s.irradiance_mu_s, s.irradiance_r, n_);
  for (std::size_t g = 0; g < group_count(); ++g) {
    unpack(groups_[g].delta_irradiance, g, n_, last.data);
    unpack(groups_[g].previous_delta_irradiance, g, n_, before.data);
  }
  atmosphere::lut::add_series_tail(last, before, tables_.irradiance);
  return tail_sum;
}

void GpuPrecompute::read_back_multiple_orders() {
  for (std::size_t g = 0; g < group_count(); ++g) {
    unpack(groups_[g].irradiance, g, n_, tables_.irradiance.data);
    unpack(groups_[g].multiple, g, n_, tables_.multiple.data);
  }
}

LookupTables GpuPrecompute::run() {
  const int orders = options_.max_orders;
  // The same stages, shares and order accounting as cpu_precompute.cpp.
  const double share_multiple = orders > 1 ? 0.85 / (orders - 1) : 0.0;
  start_programs();
  model_buffers_.bind();
  texel_coordinates_.bind_storage(kTexelCoordinates);
  row_sums_.bind_storage(kRowSums);
  stage("transmittance", 0.05, [&] { compute_transmittance(); });
  stage("single scattering", orders > 1 ? 0.10 : 0.95, [&] { compute_single_scattering(); });
  std::vector<double> order_sums;
  order_sums.push_back(radiance_sum(true));
  int used = 1;
  // The orders after the last one, as its geometric tail (series_tail.h): from
  // the third order on, where the two last orders are both multiple scattering.
  const auto tail_follows = [&](int last_order) { return options_.series_tail && last_order >= 3; };
  for (int order = 2; order <= orders; ++order) {
    const std::string prefix = "order " + std::to_string(order) + ": ";
    stage(prefix + "scattering density", share_multiple * 0.6, [&] { compute_scattering_density(order); });
    stage(prefix + "sky irradiance", share_multiple * 0.1, [&] { compute_indirect_irradiance(order); });
    bool last = false;
    stage(prefix + "multiple scattering", share_multiple * 0.3, [&] {
      const double added = compute_multiple_scattering(options_.ray_sample_stride(order));
      order_sums.push_back(added);
      double total = 0.0;
      for (double v : order_sums) total += v;
      last = order == orders || (options_.tolerance > 0.0 && total > 0.0 && added < options_.tolerance * total);
      // The tables are final: their readback is part of this stage, or of the tail's.
      if (last && !tail_follows(order)) read_back_multiple_orders();
    });
    used = order;
    if (last) break;
  }
  double tail_sum = 0.0;
  if (tail_follows(used)) {
    stage("series tail", 0.0, [&] { tail_sum = add_series_tail(); });
  }
  tables_.scattering_orders = used;
  tables_.hash = atmosphere::lookup_table_hash(model_);
  if (report_) {
    report_->set_order_sums(order_sums, tail_sum);
    report_->device = context_.renderer();
  }
  if (options_.progress) options_.progress({"done", 1.0});
  return std::move(tables_);
}

}  // namespace

LookupTables precompute_tables_gpu(const AtmosphereModel& model, const PrecomputeOptions& options,
                                   PrecomputeReport* report, const gl::HeadlessContext* context, GpuPrecision precision,
                                   const std::optional<std::filesystem::path>& program_cache, gl::CompileMode compile) {
  options.sizes.check();
  std::optional<gl::HeadlessContext> own;
  if (context == nullptr) {
    own.emplace();
    context = &*own;
  } else if (!context->is_current()) {
    context->make_current();
  }
  const bool fp64 =
      precision == GpuPrecision::fp64 || (precision == GpuPrecision::automatic && context->gl_major() >= 4);
  spdlog::debug("GPU precompute on '{}' in {}", context->renderer(), fp64 ? "fp64" : "fp32");
  gl::check_gl_error("GPU precompute: an earlier GL call left an error");
  std::optional<gl::ProgramBinaryCache> binaries;
  if (program_cache) binaries.emplace(*program_cache);
  const auto start = std::chrono::steady_clock::now();
  GpuPrecompute precompute(model, options, report, *context, fp64, binaries ? &*binaries : nullptr, compile);
  LookupTables tables = precompute.run();
  spdlog::debug("GPU precompute: {}", precompute.builds().summary());
  if (binaries)
    spdlog::debug(
        "GPU precompute: {} programs from the binary cache in {}, {} compiled and stored, {} refused ({:.2f} s)",
        binaries->statistics().loaded, binaries->directory().string(), binaries->statistics().stored,
        binaries->statistics().refused, seconds_since(start));
  return tables;
}

}  // namespace zenith::render
