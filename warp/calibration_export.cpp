#include "warp/calibration_export.h"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <fstream>
#include <stdexcept>
#include <system_error>
#include <utility>

#include <nlohmann/json.hpp>

#include "image/image_writer.h"
#include "warp/blend_map.h"
#include "warp/blending.h"
#include "warp/export_warp_map.h"
#include "warp/mpcdi_writer.h"
#include "warp/pfm.h"
#include "warp/planar_projection.h"
#include "warp/warped_projection.h"

namespace zenith::app {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

/// The display encoding of the exported maps: a pure power, as MPCDI's
/// gammaEmbedded and a viewport blend file's "gamma" decode it.
constexpr double kDisplayGamma = 2.2;
/// The warp map's conventions, written into the viewport config and the sidecar.
constexpr warp::PfmRowOrder kWarpRowOrder = warp::PfmRowOrder::top_to_bottom;

void write_file(const fs::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (out) out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (out) out.close();
  if (!out)
    throw std::runtime_error(path.string() + ": cannot write the file (" +
                             std::error_code(errno, std::generic_category()).message() + ")");
}

/// One 16-bit map in both encodings; their sidecar entries.
json write_map_pair(const fs::path& dir, const std::string& stem, const std::string& kind, int width, int height,
                    const std::vector<float>& values, std::vector<ExportedFile>& written) {
  json entries = json::array();
  for (const double gamma : {1.0, kDisplayGamma}) {
    const bool linear = gamma == 1.0;
    const std::string file = stem + (linear ? "-linear.png" : "-gamma2.2.png");
    const std::string encoding = linear ? "linear" : "gamma 2.2";
    const std::string decode = linear ? "value = stored / 65535" : "value = (stored / 65535)^2.2";
    image::write_png_grey16(dir / file, width, height, warp::encode_map_16(values, gamma), gamma,
                            {{"zenith:map", kind}, {"zenith:encoding", encoding + ": " + decode}});
    written.push_back(
        {dir / file, fmt::format("{}, 16-bit grey PNG {} x {} px, {} ({})", kind, width, height, encoding, decode)});
    entries.push_back({{"file", file},
                       {"kind", kind},
                       {"format", "PNG, 16-bit greyscale"},
                       {"size_px", {width, height}},
                       {"encoding", encoding},
                       {"gamma", gamma},
                       {"decode", decode}});
  }
  return entries;
}

/// The pinhole of an output the sl profile can describe: its projection when
/// planar, or the planar base of its warp; std::invalid_argument naming the
/// output otherwise.
const warp::PlanarProjection& pinhole_of(const warp::OutputConfig& o) {
  const warp::Projection* image = o.projection.get();
  if (const auto* warped = dynamic_cast<const warp::WarpedProjection*>(image)) image = &warped->base();
  const auto* planar = dynamic_cast<const warp::PlanarProjection*>(image);
  if (planar == nullptr)
    throw std::invalid_argument("output '" + o.name +
                                "': the MPCDI sl profile describes a pinhole projector (a "
                                "frustum), and the output's projection is " +
                                image->describe() + ": export it with the 2d profile");
  return *planar;
}

}  // namespace

std::vector<ExportedFile> export_calibration(const warp::ViewportConfig& config,
                                             const std::vector<std::size_t>& indices, const fs::path& dir,
                                             const CalibrationExportOptions& options) {
  for (const std::size_t i : indices) config.require_renderable(i);
  const bool shader_lamps = options.mpcdi_profile == warp::MpcdiProfile::shader_lamps;
  if (shader_lamps)
    for (const std::size_t i : indices) pinhole_of(config.outputs.at(i));
  std::error_code error;
  fs::create_directories(dir, error);
  if (error || !fs::is_directory(dir))
    throw std::runtime_error(dir.string() + ": cannot create the export folder (" +
                             (error ? error.message() : std::string("not a directory")) + ")");

  std::vector<ExportedFile> written;
  json pfm_outputs = json::array(), mpcdi_outputs = json::array(), sidecar_outputs = json::array();
  for (const std::size_t index : indices) {
    const warp::OutputConfig& o = config.outputs.at(index);
    const int width = o.width_px, height = o.height_px;
    json files = json::array();

    // The warp, as PFM.
    const warp::ExportedWarpMap warp_map = warp::export_warp_map(o);
    const std::string warp_file = o.name + ".warp.pfm";
    write_file(dir / warp_file, warp::encode_pfm(warp_map.map, kWarpRowOrder));
    written.push_back(
        {dir / warp_file,
         fmt::format("warp, PFM {} x {} nodes (u, v, 0) at every pixel centre and corner, rows top "
                     "first, absolute, v down, NaN = no data; source {} x {} px",
                     warp_map.map.width, warp_map.map.height, warp_map.source_width_px, warp_map.source_height_px)});
    files.push_back({{"file", warp_file},
                     {"kind", "warp"},
                     {"format", "PFM, 3 channels (u, v, 0), binary32 little endian"},
                     {"size_px", {warp_map.map.width, warp_map.map.height}},
                     {"nodes",
                      "node (i, j) at the output's pixel position (i / 2, j / 2), row 0 at the top: the "
                      "odd nodes are the pixel centres, the even ones the pixel corners"},
                     {"row_order", "top_to_bottom"},
                     {"v_direction", "down"},
                     {"values", "absolute"},
                     {"units", "(u, v) normalized in the source image, (0, 0) its top-left corner"},
                     {"no_data", "NaN"},
                     {"source_size_px", {warp_map.source_width_px, warp_map.source_height_px}}});

    // The blend mask (times the warp's intensity) and the black-level map.
    const warp::BlendMask mask = warp::output_blend_mask(config, index);
    const std::vector<float> beta = warp::black_level_map(o, mask);
    for (json& entry : write_map_pair(dir, o.name + ".alpha", "blend mask", width, height, mask.alpha, written))
      files.push_back(std::move(entry));
    for (json& entry : write_map_pair(dir, o.name + ".beta", "black-level map", width, height, beta, written))
      files.push_back(std::move(entry));
    // β as one number (a viewport config's black_level) where it is one; an
    // output whose β is a map (an MPCDI region's beta map) keeps it only in
    // the maps and the archive, which viewport-mpcdi.json reads.
    const bool beta_uniform = std::all_of(beta.begin(), beta.end(), [&](float b) { return b == beta.front(); });
    const double black_level = mask.beta.empty() ? o.black_level : static_cast<double>(beta.front());

    // The MPCDI archive of the same files (the linear maps).
    const std::string alpha_file = o.name + ".alpha-linear.png", beta_file = o.name + ".beta-linear.png";
    // MPCDI: the region's resolution is the size of its image, which the warp
    // addresses (a reader takes it as the source's size).
    warp::MpcdiRegionExport region;
    region.id = o.name;
    region.width_px = warp_map.source_width_px;
    region.height_px = warp_map.source_height_px;
    region.warp_member = warp_file;
    region.warp_columns = warp_map.map.width;
    region.warp_rows = warp_map.map.height;
    region.interpolation = warp::WarpInterpolation::bilinear;
    region.alpha_member = alpha_file;
    region.alpha_gamma_embedded = 1.0;
    region.beta_member = beta_file;
    std::vector<std::pair<std::string, fs::path>> members = {{alpha_file, dir / alpha_file},
                                                             {beta_file, dir / beta_file}};
    // sl: the pinhole's frustum exactly; a warp becomes the lens distortion map.
    const bool distortion = shader_lamps && o.warp.has_value();
    if (shader_lamps) {
      region.profile = warp::MpcdiProfile::shader_lamps;
      region.frustum = pinhole_of(o).frustum();
      if (!distortion) region.warp_member.clear();
    }
    if (!shader_lamps || distortion) members.insert(members.begin(), {warp_file, dir / warp_file});
    const std::string mpcdi_file = o.name + ".mpcdi";
    warp::write_mpcdi_archive(dir / mpcdi_file, warp::mpcdi_descriptor(region), members);
    std::vector<std::string> member_names = {"mpcdi.xml"};
    for (const auto& member : members) member_names.push_back(member.first);
    if (shader_lamps) {
      const warp::PlanarFrustum& f = region.frustum;
      written.push_back(
          {dir / mpcdi_file,
           fmt::format("MPCDI sl profile, region '{}' {} x {} px: mpcdi.xml (frustum left {} right {} "
                       "down {} up {} yaw {} pitch {} roll {} degrees, coordinate frame at the origin "
                       "with the display's axes), {}{} (gammaEmbedded 1), {}",
                       o.name, region.width_px, region.height_px, f.left_deg, f.right_deg, f.down_deg, f.up_deg,
                       f.yaw_deg, f.pitch_deg, f.roll_deg,
                       distortion ? warp_file + " (lens distortion map), " : std::string(), alpha_file, beta_file)});
    } else {
      written.push_back(
          {dir / mpcdi_file, fmt::format("MPCDI 2d profile, region '{}' {} x {} px (the source): "
                                         "mpcdi.xml, {}, {} (gammaEmbedded 1), {}",
                                         o.name, region.width_px, region.height_px, warp_file, alpha_file, beta_file)});
    }
    files.push_back(
        {{"file", mpcdi_file},
         {"kind", "MPCDI"},
         {"format", shader_lamps ? "ZIP: mpcdi.xml (profile sl, version 2.0: the output's frustum and a coordinate "
                                   "frame with the display's axes (X left, Y up, Z forward)), the warp as the lens "
                                   "distortion map (2D PFM) where the output has one, alpha map and beta map (16-bit "
                                   "grey PNG, linear, gammaEmbedded 1)"
                                 : "ZIP: mpcdi.xml (profile 2d, version 2.0), geometry warp PFM (interpolation "
                                   "linear), alpha map and beta map (16-bit grey PNG, linear, gammaEmbedded 1)"},
         {"region", o.name},
         {"members", member_names}});

    // The outputs of the exported viewport configs.
    const json source = {{"size_px", {warp_map.source_width_px, warp_map.source_height_px}}};
    const json base = {{"name", o.name}, {"size", {width, height}}, {"projection", o.projection_spec}};
    json pfm_output = base, mpcdi_output = base;
    pfm_output["blend"] = {{"file", alpha_file}, {"gamma", 1.0}};
    if (beta_uniform) pfm_output["black_level"] = black_level;
    // The archive's own alpha and beta maps: α, and β per pixel.
    mpcdi_output["blend"] = {{"type", "mpcdi"}};
    pfm_output["warp"] = {{"file", warp_file},     {"format", "pfm"},      {"row_order", "top_to_bottom"},
                          {"v_direction", "down"}, {"values", "absolute"}, {"source", source}};
    mpcdi_output["warp"] = {
        {"file", mpcdi_file}, {"format", "mpcdi"}, {"region", o.name}, {"values", "absolute"}, {"source", source}};
    if (shader_lamps) {  // the region gives the rays: its frustum and frame, its resolution the source
      mpcdi_output.erase("projection");
      mpcdi_output["warp"] = {{"file", mpcdi_file}, {"format", "mpcdi"}, {"region", o.name}};
    }
    pfm_outputs.push_back(std::move(pfm_output));
    mpcdi_outputs.push_back(std::move(mpcdi_output));
    sidecar_outputs.push_back({{"name", o.name},
                               {"size_px", {width, height}},
                               {"projection", o.projection_spec},
                               {"blend", warp::to_string(o.blend.mode)},
                               {"black_level", beta_uniform ? json(black_level) : json("per pixel: the beta maps")},
                               {"files", std::move(files)}});
  }

  const auto viewport = [&](const char* kind, json outputs) {
    return json{{"zenith_viewports", warp::kViewportConfigVersion},
                {"name", config.name},
                {"description", fmt::format("exported by zenith export-calibration from {}: warps as {}, blend "
                                            "masks as linear 16-bit PNG",
                                            config.source, kind)},
                {"outputs", std::move(outputs)}};
  };
  write_file(dir / "viewport-pfm.json", viewport("PFM", std::move(pfm_outputs)).dump(2) + "\n");
  written.push_back({dir / "viewport-pfm.json", "viewport config of the exported outputs, warps read from the PFMs"});
  write_file(dir / "viewport-mpcdi.json", viewport("MPCDI", std::move(mpcdi_outputs)).dump(2) + "\n");
  written.push_back(
      {dir / "viewport-mpcdi.json", "viewport config of the exported outputs, warps read from the MPCDI archives"});

  const json sidecar = {{"zenith_calibration_export", 1},
                        {"viewport", config.source},
                        {"name", config.name},
                        {"output_stage",
                         "P' = P * alpha * (1 - beta) + beta, P display-linear (a fraction of full white), then the "
                         "display encoding (docs/viewports.md)"},
                        {"viewport_configs", {{"pfm", "viewport-pfm.json"}, {"mpcdi", "viewport-mpcdi.json"}}},
                        {"docs", "docs/warp-meshes.md, \"Exporting to warp engines and media servers\""},
                        {"outputs", std::move(sidecar_outputs)}};
  write_file(dir / "calibration.json", sidecar.dump(2) + "\n");
  written.push_back({dir / "calibration.json", "sidecar: every file, its size, encoding and conventions"});
  return written;
}

std::vector<ExportedFile> export_calibration(const warp::ViewportConfig& config, const std::string& output_name,
                                             const fs::path& dir, const CalibrationExportOptions& options) {
  std::vector<std::size_t> indices;
  if (!output_name.empty()) {
    indices.push_back(config.index_of(output_name));
  } else {
    for (std::size_t i = 0; i < config.outputs.size(); ++i) indices.push_back(i);
  }
  return export_calibration(config, indices, dir, options);
}

}  // namespace zenith::app
