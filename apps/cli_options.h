#pragma once
// Command-line options shared by several commands: the images they write
// (`zenith render`, `zenith show render`: EXR pixel type, PNG tone mapping,
// spectral-to-RGB mapping; docs/colour.md), the lookup tables they use
// (sizes, orders, cache, where missing ones are computed; docs/lookup-tables.md),
// the view without a viewport config and the GL device they render on.
#include <fmt/format.h>

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "atmosphere/lut/precompute_options.h"
#include "atmosphere/named_inputs.h"

namespace zenith::app {

inline void add_image_options(CLI::App* cmd, std::string& exr_type, std::string& tone, std::string& colour) {
  cmd->add_option("--exr-type", exr_type, "EXR pixels: half (default) or float")
      ->check(CLI::IsMember({"half", "float"}));
  cmd->add_option("--tone", tone, "PNG tone mapping: exponential (paper, default) or clamp")
      ->check(CLI::IsMember({"exponential", "clamp"}));
  cmd->add_option("--colour", colour, "Spectral to RGB: auto, direct, cie1931")
      ->check(CLI::IsMember({"auto", "direct", "cie1931"}));
}

/// --projection planar|fisheye, --fov, --tilt and --size WIDTHxHEIGHT: a view
/// without a viewport config; the help of --projection and --size says the
/// command's defaults.
inline void add_view_options(CLI::App* cmd, std::string& projection, const std::string& projection_help,
                             std::optional<double>& fov_deg, std::optional<double>& tilt_deg, std::string& size,
                             const std::string& size_help) {
  cmd->add_option("--projection", projection, projection_help)->check(CLI::IsMember({"planar", "fisheye"}));
  cmd->add_option("--fov", fov_deg, "Field of view [deg]: planar horizontal (default 60), fisheye (default 180)");
  cmd->add_option("--tilt", tilt_deg, "Fisheye: axis tilted from the zenith toward forward [deg]");
  cmd->add_option("--size", size, size_help);
}

/// --tables paper|twilight|small|large, --orders N, --cache DIR.
inline void add_table_options(CLI::App* cmd, std::string& tables, int& orders, std::string& cache_dir) {
  cmd->add_option("--tables", tables,
                  "Table sizes: paper (default), twilight (128 mu_s texels and 200 ray samples, for dusk and night), "
                  "small, large")
      ->check(CLI::IsMember(atmosphere::table_size_names()));
  const std::string orders_help =
      "Scattering orders of the tables (default " + std::to_string(atmosphere::lut::kDefaultScatteringOrders) + ")";
  cmd->add_option("--orders", orders, orders_help)->check(CLI::Range(1, 50));
  cmd->add_option("--cache", cache_dir, "Table cache directory (default $XDG_CACHE_HOME/zenith)");
}

/// --cpu-precompute: compute missing tables on the CPU instead of the GPU.
inline void add_cpu_precompute_flag(CLI::App* cmd, bool& cpu_precompute) {
  cmd->add_flag("--cpu-precompute", cpu_precompute, "Precompute missing tables on the CPU");
}

/// --device auto|software|hardware: the GL device to render on.
inline void add_gl_device_option(CLI::App* cmd, std::string& device) {
  cmd->add_option("--device", device, "GL device: auto, software (llvmpipe), hardware")
      ->check(CLI::IsMember({"auto", "software", "hardware"}));
}

/// A band of wavelengths FIRST,LAST [nm] (`zenith colour --band-nm`, `zenith
/// sample --colour-band-nm`): two numbers in 100–100 000 nm; the order is
/// checked by check_wavelength_band once the command runs.
inline void add_wavelength_band_option(CLI::App* cmd, const std::string& name, std::vector<double>& band_nm,
                                       const std::string& help) {
  cmd->add_option(name, band_nm, help)->delimiter(',')->expected(2)->check(CLI::Range(100.0, 100000.0));
}

/// Throws std::invalid_argument naming `name` where the band's first wavelength is not below its last.
inline void check_wavelength_band(const std::string& name, const std::vector<double>& band_nm) {
  if (!(band_nm[0] < band_nm[1]))
    throw std::invalid_argument(
        fmt::format("{} {},{}: the band's first wavelength must be below its last", name, band_nm[0], band_nm[1]));
}

}  // namespace zenith::app
