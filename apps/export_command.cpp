// `zenith export-calibration`: the warp, blend mask and black-level map of the
// outputs of a viewport config, as files for projectors and media servers that
// warp and blend themselves (PFM, MPCDI, 16-bit PNG; warp/calibration_export.h,
// docs/warp-meshes.md "Exporting to warp engines and media servers").
#include <fmt/format.h>

#include <memory>
#include <string>

#include "warp/calibration_export.h"
#include "apps/commands.h"
#include "offline/output_rendering.h"

namespace zenith::app {

void register_export_calibration_command(CLI::App& app) {
  struct Args {
    std::string viewport, out;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand(
      "export-calibration",
      "Export the warp (PFM, MPCDI), blend mask and black-level map (16-bit PNG, linear and gamma 2.2) of each "
      "output of a viewport config for hardware that warps and blends itself (docs/warp-meshes.md)");
  cmd->add_option("--viewport", args->viewport,
                  "The viewport config, CONFIG.json#NAME for one output, CONFIG.json for all")
      ->required();
  cmd->add_option("--out", args->out, "The folder to write into (created when missing)")->required();
  cmd->callback([args] {
    const ViewportSelection selection = select_viewport_outputs(args->viewport);
    const std::vector<ExportedFile> files = export_calibration(selection.config, selection.indices, args->out);
    for (const ExportedFile& f : files) fmt::print("written {}: {}\n", f.path.string(), f.summary);
  });
}

}  // namespace zenith::app
