#pragma once
// Command-line options shared by the commands that write images (`zenith
// render`, `zenith show render`): the EXR pixel type, the PNG tone mapping and
// the spectral-to-RGB mapping (docs/colour.md).
#include <string>

#include <CLI/CLI.hpp>

namespace zenith::app {

inline void add_image_options(CLI::App* cmd, std::string& exr_type, std::string& tone, std::string& colour) {
  cmd->add_option("--exr-type", exr_type, "EXR pixels: half (default) or float")->check(CLI::IsMember({"half", "float"}));
  cmd->add_option("--tone", tone, "PNG tone mapping: exponential (paper, default) or clamp")
      ->check(CLI::IsMember({"exponential", "clamp"}));
  cmd->add_option("--colour", colour, "Spectral to RGB: auto, direct, cie1931")
      ->check(CLI::IsMember({"auto", "direct", "cie1931"}));
}

}  // namespace zenith::app
