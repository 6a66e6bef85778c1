// `zenith displays`: the monitors this machine's window system offers, as an
// output's "window" names them (docs/window.md, "Outputs on displays").
#include <fmt/format.h>

#include "apps/commands.h"
#include "render/window/monitors.h"

namespace zenith::app {

void register_displays_command(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand(
      "displays",
      "List the monitors (name, index, size, position, refresh) an output's \"window\" can name (docs/window.md)");
  cmd->callback([] {
    const std::vector<render::window::MonitorInfo> monitors = render::window::list_monitors();
    fmt::print("{} monitor{} (index: name size at (x, y) on the desktop):\n{}", monitors.size(),
               monitors.size() == 1 ? "" : "s", render::window::describe_monitors(monitors));
  });
}

}  // namespace zenith::app
