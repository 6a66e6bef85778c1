#pragma once
// Command-line options shared by several commands: the images they write
// (`zenith render`, `zenith show render`: EXR pixel type, PNG tone mapping,
// spectral-to-RGB mapping; docs/colour.md) and the lookup tables they use
// (sizes, orders, cache; docs/lookup-tables.md).
#include <string>

#include <CLI/CLI.hpp>

#include "atmosphere/lut/precompute_options.h"

namespace zenith::app {

inline void add_image_options(CLI::App* cmd, std::string& exr_type, std::string& tone, std::string& colour) {
  cmd->add_option("--exr-type", exr_type, "EXR pixels: half (default) or float")->check(CLI::IsMember({"half", "float"}));
  cmd->add_option("--tone", tone, "PNG tone mapping: exponential (paper, default) or clamp")
      ->check(CLI::IsMember({"exponential", "clamp"}));
  cmd->add_option("--colour", colour, "Spectral to RGB: auto, direct, cie1931")
      ->check(CLI::IsMember({"auto", "direct", "cie1931"}));
}

/// --tables paper|small|large, --orders N, --cache DIR.
inline void add_table_options(CLI::App* cmd, std::string& tables, int& orders, std::string& cache_dir) {
  cmd->add_option("--tables", tables, "Table sizes: paper (default), small, large")
      ->check(CLI::IsMember({"paper", "small", "large"}));
  const std::string orders_help =
      "Scattering orders of the tables (default " + std::to_string(atmosphere::lut::kDefaultScatteringOrders) + ")";
  cmd->add_option("--orders", orders, orders_help)->check(CLI::Range(1, 50));
  cmd->add_option("--cache", cache_dir, "Table cache directory (default $XDG_CACHE_HOME/zenith)");
}

}  // namespace zenith::app
