#pragma once
// Subcommands of the `zenith` executable. Each registers itself on the CLI11 app.
#include <CLI/CLI.hpp>

namespace zenith::app {

/// `zenith atmosphere show|list`.
void register_atmosphere_command(CLI::App& app);
/// `zenith precompute`.
void register_precompute_command(CLI::App& app);
/// `zenith sample`.
void register_sample_command(CLI::App& app);
/// `zenith colour` (apps/colour_command.cpp).
void register_colour_command(CLI::App& app);
/// `zenith render`.
void register_render_command(CLI::App& app);
/// `zenith export-calibration` (apps/export_command.cpp).
void register_export_calibration_command(CLI::App& app);
/// `zenith master`, `zenith node`, `zenith cluster` (apps/cluster_commands.cpp).
void register_cluster_commands(CLI::App& app);
/// `cluster check` under `cluster` (apps/cluster_check_command.cpp).
void register_cluster_check(CLI::App& cluster);
/// `zenith displays` (apps/displays_command.cpp).
void register_displays_command(CLI::App& app);
/// `zenith validate cie|eclipse|measured|night|stress` (apps/validate_command.cpp).
void register_validate_command(CLI::App& app);
/// `validate stress` under `validate` (apps/validate_stress.cpp).
void register_validate_stress(CLI::App& validate);
/// `zenith timecode write|read` (apps/timecode_command.cpp).
void register_timecode_command(CLI::App& app);
/// `zenith show ...` (apps/show_command.cpp).
void register_show_command(CLI::App& app);
/// `show render` under `show` (apps/show_render.cpp).
void register_show_render(CLI::App& show);
/// `show plan` under `show` (apps/show_render.cpp).
void register_show_plan(CLI::App& show);
/// `show control` under `show` (apps/show_control.cpp).
void register_show_control(CLI::App& show);

}  // namespace zenith::app
