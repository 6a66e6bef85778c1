// `zenith show`: the show subcommands (docs/shows.md).
#include "apps/commands.h"

namespace zenith::app {

void register_show_command(CLI::App& app) {
  CLI::App* show = app.add_subcommand("show", "Shows: render offline, plan tables (docs/shows.md)");
  show->require_subcommand(1);
  register_show_render(*show);
  register_show_plan(*show);
}

}  // namespace zenith::app
