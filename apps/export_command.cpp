// `zenith export-calibration`: the warp, blend mask and black-level map of the
// outputs of a viewport config, as files for projectors and media servers that
// warp and blend themselves (PFM, MPCDI, 16-bit PNG; warp/calibration_export.h,
// docs/warp-meshes.md "Exporting to warp engines and media servers").
#include <fmt/format.h>

#include <memory>
#include <string>

#include "apps/commands.h"
#include "offline/output_rendering.h"
#include "warp/calibration_export.h"

namespace zenith::app {

void register_export_calibration_command(CLI::App& app) {
  struct Args {
    std::string viewport, out, mpcdi_profile = "2d";
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
  cmd->add_option("--mpcdi-profile", args->mpcdi_profile,
                  "The MPCDI archives' profile: 2d (the warp of each output's source image) or sl (shader lamps: "
                  "a planar output's frustum and coordinate frame, its warp as the lens distortion map)")
      ->check(CLI::IsMember({"2d", "sl"}))
      ->capture_default_str();
  cmd->callback([args] {
    const ViewportSelection selection = select_viewport_outputs(args->viewport);
    CalibrationExportOptions options;
    if (args->mpcdi_profile == "sl") options.mpcdi_profile = warp::MpcdiProfile::shader_lamps;
    const std::vector<ExportedFile> files = export_calibration(selection.config, selection.indices, args->out, options);
    for (const ExportedFile& f : files) fmt::print("written {}: {}\n", f.path.string(), f.summary);
  });
}

}  // namespace zenith::app
