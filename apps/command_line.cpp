#include "apps/command_line.h"

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <exception>

#include "apps/commands.h"
#include "core/json_reader.h"

namespace zenith::app {

int run_command_line(int argc, char** argv) {
  // Logs go to stderr: stdout carries command output (CSV, JSON) that may be piped.
  spdlog::set_default_logger(spdlog::stderr_color_mt("zenith"));
  CLI::App app{"zenith: physically based planetary atmospheres for planetarium domes and projector clusters"};
  app.require_subcommand(1);
  std::string log_level = "info";
  app.add_option("--log-level", log_level, "trace, debug, info, warn, error, off")
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error", "off"}));
  app.parse_complete_callback([&] { spdlog::set_level(spdlog::level::from_str(log_level)); });

  register_atmosphere_command(app);
  register_precompute_command(app);
  register_sample_command(app);
  register_colour_command(app);
  register_render_command(app);
  register_export_calibration_command(app);
  register_cluster_commands(app);
  register_displays_command(app);
  register_validate_command(app);
  register_show_command(app);
  register_timecode_command(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const ConfigError& e) {
    spdlog::error("{}", e.what());
    return 2;
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
  return 0;
}

}  // namespace zenith::app
