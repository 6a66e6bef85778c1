// `zenith show`: the show subcommands (docs/shows.md).
#include "apps/commands.h"

namespace zenith::app {

void register_show_command(CLI::App& app) {
  CLI::App* show = app.add_subcommand(
      "show",
      "Shows: render offline, plan tables, control playback (docs/shows.md; play one with `zenith cluster --show`)");
  show->require_subcommand(1);
  register_show_render(*show);
  register_show_plan(*show);
  register_show_control(*show);
}

}  // namespace zenith::app
