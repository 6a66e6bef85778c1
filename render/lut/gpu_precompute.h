#pragma once
// GPU implementation of the lookup-table precomputation (paper section 5.1):
// GL 4.5 compute shaders (shaders/transmittance.comp, single_scattering.comp,
// scattering_density.comp, indirect_irradiance.comp, multiple_scattering.comp,
// sharing shaders/atmosphere_common.glsl) on a headless EGL context. Mesa
// llvmpipe where there is no GPU, NVIDIA's EGL where there is one.
//
// It mirrors atmosphere/lut/cpu_precompute.cpp operation for operation and
// returns the same tables (same LookupTables layout, channels = wavelengths),
// the same report (stage names, orders used, order fractions; device = the GL
// renderer string) and the same progress callbacks for the same options.
//
// Wavelengths are processed in groups of 4, one dispatch per group: group g's
// tables are RGBA32F textures holding wavelengths 4g..4g+3, so a model with N
// wavelengths uses ceil(N/4) textures per table (N ≤ 64). Shaders are compiled
// per model with #defines that drop what the model does not have (no Mie, no
// absorbers, no air-mass stretch), and per precision.
#include <filesystem>
#include <optional>

#include "atmosphere/atmosphere_model.h"
#include "atmosphere/lut/lookup_tables.h"
#include "atmosphere/lut/precompute_options.h"
#include "render/gl/egl_context.h"
#include "render/gl/shader_build.h"

namespace zenith::render {

/// Arithmetic of the shaders. Tables are float32 in every case.
enum class GpuPrecision {
  automatic,  ///< fp64 (double is core in GL 4.0+, so every GL 4.5 context has it)
  fp64,       ///< geometry, sums and table interpolation in double, as on the CPU (agreement ~1e-6)
  fp32,       ///< everything in float: faster on GPUs with slow double, agreement ~1e-2 (see docs)
};
/// "auto", "fp64", "fp32".
const char* to_string(GpuPrecision precision);

/// Computes the tables on the GPU. Uses `context` (made current on this thread if
/// it is not) or, when null, creates a HeadlessContext for the call. With
/// `program_cache`, the linked programs are kept there between runs
/// (render/gl/program_binary_cache.h; zenith uses <table cache>/programs).
/// The programs' builds all start at the beginning, each finished where first
/// used, so that a driver with parallel shader compile builds them at once;
/// CompileMode::serial builds each where first used, one at a time, and
/// CompileMode::contexts each on a thread and context of its own, all at once
/// (render/gl/program_builds.h; `zenith precompute --serial-compile`,
/// `--compile-contexts`).
/// Throws std::invalid_argument for bad options (as the CPU path),
/// std::runtime_error when no GL context can be created or a table exceeds the
/// GL limits, gl::ShaderBuildError when the driver refuses a program.
atmosphere::lut::LookupTables precompute_tables_gpu(const atmosphere::AtmosphereModel& model,
                                                    const atmosphere::lut::PrecomputeOptions& options,
                                                    atmosphere::lut::PrecomputeReport* report = nullptr,
                                                    const gl::HeadlessContext* context = nullptr,
                                                    GpuPrecision precision = GpuPrecision::automatic,
                                                    const std::optional<std::filesystem::path>& program_cache = {},
                                                    gl::CompileMode compile = gl::CompileMode::parallel);

}  // namespace zenith::render
