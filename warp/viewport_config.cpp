#include "warp/viewport_config.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <initializer_list>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <tuple>
#include <utility>

#include "core/json_reader.h"
#include "core/strings.h"
#include "core/units.h"
#include "warp/mpcdi.h"
#include "warp/mpcdi_blend.h"
#include "warp/mpcdi_projection.h"
#include "warp/projection_factory.h"
#include "warp/warp_mesh.h"
#include "warp/warped_projection.h"

namespace zenith::warp {
namespace {

using config::brief;
using core::cat;

using nlohmann::json;
namespace fs = std::filesystem;

constexpr int kMaxOutputs = 256;
constexpr int kMaxSidePx = 16384;
constexpr double kMaxBlackLevel = 0.5;
constexpr double kMinBlendWidthFraction = 1e-3, kMaxBlendWidthFraction = 0.5;
constexpr double kMinMaskGamma = 0.1, kMaxMaskGamma = 10.0;
constexpr std::size_t kMaxNameLength = 64;
constexpr double kMinSourceAspect = 0.1, kMaxSourceAspect = 10.0;
/// The values of a Bourke warp's "fit", in the order the errors list them.
constexpr MeshFit kMeshFits[] = {MeshFit::height, MeshFit::width, MeshFit::crop, MeshFit::letterbox, MeshFit::stretch};

void allow_keys(const JsonReader& r, const json& object, std::initializer_list<std::string_view> allowed) {
  config::reject_unknown_keys(r, object, allowed, "docs/viewports.md");
}

bool valid_name(const std::string& name) {
  return !name.empty() && name.size() <= kMaxNameLength && name != "." && name != ".." &&
         std::all_of(name.begin(), name.end(), [](char c) {
           return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' || c == '_' ||
                  c == '.';
         });
}

/// `key` ("size", "size_px"): [width, height], integers in [1, 16384].
std::pair<int, int> read_size(JsonReader& r, const std::string& size_key = "size") {
  const json& v = r.raw(size_key);
  if (!v.is_array() || v.size() != 2) r.fail(size_key, cat("= ", brief(v), ": must be [width, height] in pixels"));
  int side[2] = {0, 0};
  for (std::size_t k = 0; k < 2; ++k) {
    const json& s = v[k];
    const std::string key = cat(size_key, "/", k);
    if (!s.is_number_integer()) r.fail(key, cat("= ", brief(s), ": must be an integer in [1, ", kMaxSidePx, "] px"));
    const auto x = s.get<long long>();
    if (x < 1 || x > kMaxSidePx) r.fail(key, cat("= ", x, ": must be in [1, ", kMaxSidePx, "] px"));
    side[k] = static_cast<int>(x);
  }
  return {side[0], side[1]};
}

/// An MPCDI region's alpha and beta maps, for a "blend" of type "mpcdi".
struct RegionMaps {
  std::shared_ptr<const MpcdiBlendMap> alpha, beta;  ///< null where the region has none
  std::string source;                                ///< "<archive>:<descriptor>" (messages)
};

/// A warp's mesh and what its file says about the source image.
struct LoadedWarp {
  std::optional<WarpMesh> mesh;  ///< set unless `projection` is
  /// MPCDI: the region's xResolution × yResolution, the size of the region's
  /// image the warp's (x, y) address; nothing for the other formats.
  std::optional<std::pair<int, int>> source_size_px;
  /// MPCDI 3d, sl, a3: the output's whole projection, from the file (its
  /// frustum and frame, or its 3D warp; warp/mpcdi_projection.h).
  std::shared_ptr<const Projection> projection;
  std::string profile;  ///< MPCDI: the file's profile (messages)
  /// MPCDI: the region's colour profile (<color>); null without one.
  std::shared_ptr<const MpcdiColourProfile> colour;
  RegionMaps maps{};  ///< MPCDI: the region's alpha and beta maps
};

/// The mesh of a warp for an output of width × height px; resolves source.file
/// against `base_dir` (it must exist). Every failure is a ConfigError at
/// /outputs/<i>/warp/file (or .../region).
LoadedWarp load_warp(JsonReader& w, WarpSource& source, const fs::path& base_dir, int width_px, int height_px) {
  source.file = w.existing_file("file", base_dir);
  try {
    if (source.format == "bourke") {
      BourkeMeshOptions options;
      options.aspect = static_cast<double>(width_px) / height_px;  // square pixels
      options.fit = source.fit;
      return {load_bourke_mesh(source.file, options), std::nullopt, nullptr, "", nullptr};
    }
    if (source.format == "pfm")
      return {load_pfm_warp_mesh(source.file, source.row_order, WarpInterpolation::catmull_rom, source.conventions),
              std::nullopt, nullptr, "", nullptr};
    const MpcdiFile mpcdi = load_mpcdi(source.file, MpcdiLoadOptions{source.conventions.values});
    const MpcdiRegion* region = mpcdi.find_region(source.region);
    if (region == nullptr) {
      std::string ids;
      for (const MpcdiBuffer& b : mpcdi.buffers)
        for (const MpcdiRegion& g : b.regions) ids += (ids.empty() ? "" : ", ") + ("\"" + g.id + "\"");
      w.fail("region", cat("= \"", source.region, "\": no such region in ", source.file.string(),
                           " (regions: ", ids.empty() ? "none" : ids, ")"));
    }
    if (source.eye && !mpcdi_region_has_3d_warp(*region))
      w.fail("eye", cat("applies to a region with a 3D geometry warp (screen points); region \"", source.region,
                        "\" of ", source.file.string(), " (profile ", to_string(mpcdi.profile), ") has none"));
    std::shared_ptr<const MpcdiColourProfile> colour;
    if (region->colour) colour = std::make_shared<const MpcdiColourProfile>(*region->colour);
    RegionMaps maps;
    if (region->alpha_map) maps.alpha = std::make_shared<const MpcdiBlendMap>(*region->alpha_map);
    if (region->beta_map) maps.beta = std::make_shared<const MpcdiBlendMap>(*region->beta_map);
    maps.source = cat(mpcdi.path, ":", mpcdi.descriptor);
    if (mpcdi_region_defines_rays(mpcdi)) {  // 3d, sl, a3: the frustum and frame, or the 3D warp
      MpcdiViewOptions view;
      view.eye = source.eye;
      if (source.source_size_given) view.source_size_px = std::pair{source.source_width_px, source.source_height_px};
      LoadedWarp loaded;
      loaded.projection = mpcdi_region_projection(mpcdi, *region, width_px, height_px, view);
      loaded.profile = to_string(mpcdi.profile);
      loaded.colour = std::move(colour);
      loaded.maps = std::move(maps);
      return loaded;
    }
    if (!region->warp_mesh)
      w.fail("region", cat("= \"", source.region, "\": the region has no 2D geometry warp (profile ",
                           to_string(mpcdi.profile), ")"));
    return {*region->warp_mesh,
            std::pair{region->x_resolution_px, region->y_resolution_px},
            nullptr,
            "2d",
            std::move(colour),
            std::move(maps)};
  } catch (const ConfigError&) {
    throw;
  } catch (const std::exception& e) {  // the loaders' runtime_error / invalid_argument
    w.fail("file", cat("cannot use the warp: ", e.what()));
  }
}

/// The warp's "source" object, {"size_px": [w, h]} or {"aspect": a}: the size
/// of the image the mesh's (u, v) address, for an output of width × height px
/// whose projection spec is `spec`. Absent: square (side = the output's height)
/// for a fisheye source, the output's size for any other (for MPCDI, the
/// region's resolution replaces this default once the file is read).
std::pair<int, int> read_warp_source_size(JsonReader& w, const json& spec, int width_px, int height_px) {
  if (!w.has("source")) {
    const bool fisheye = spec.is_object() && spec.value("type", json()) == json("fisheye");
    return fisheye ? std::pair{height_px, height_px} : std::pair{width_px, height_px};
  }
  const json& v = w.raw("source");
  if (!v.is_object())
    w.fail("source", cat("= ", brief(v),
                         ": must be an object, {\"size_px\": [width, height]} or {\"aspect\": "
                         "width / height} (docs/warp-meshes.md)"));
  JsonReader s(v, w.file(), w.key_path("source"));
  allow_keys(s, v, {"size_px", "aspect"});
  if (s.has("size_px") && s.has("aspect"))
    s.fail("aspect", "give either size_px or aspect, not both (size_px fixes the aspect)");
  if (s.has("size_px")) return read_size(s, "size_px");
  if (!s.has("aspect")) s.fail("", "give size_px ([width, height] px) or aspect (width / height)");
  const double aspect = s.number("aspect", kMinSourceAspect, kMaxSourceAspect, "(width / height)");
  const long long source_width = std::max(1LL, std::llround(aspect * height_px));
  if (source_width > kMaxSidePx)
    s.fail("aspect", cat("= ", aspect, ": the source would be ", source_width, " px wide at the output's height of ",
                         height_px, " px, more than ", kMaxSidePx, ": give size_px instead"));
  return {static_cast<int>(source_width), height_px};
}

/// MPCDI "eye": [x, y, z], finite numbers: the origin of a 3D warp's rays in
/// the display's frame and the warp's unit; nothing when absent.
std::optional<glm::dvec3> read_eye(JsonReader& w) {
  if (!w.has("eye")) return std::nullopt;
  const json& v = w.raw("eye");
  if (!v.is_array() || v.size() != 3 ||
      !std::all_of(v.begin(), v.end(), [](const json& c) { return c.is_number() && std::isfinite(c.get<double>()); }))
    w.fail("eye", cat("= ", brief(v),
                      ": must be [x, y, z], finite numbers: the eye in the MPCDI file's 3D frame "
                      "and unit (docs/warp-meshes.md)"));
  return glm::dvec3(v[0].get<double>(), v[1].get<double>(), v[2].get<double>());
}

/// The "warp" object: {"file", "format", "region" (mpcdi), "values" (pfm,
/// mpcdi), "row_order", "v_direction" (pfm), "fit" (bourke), "source"}: its keys and values;
/// the file is looked for by load_warp(). The source's size defaults as
/// read_warp_source_size() says.
WarpSource read_warp_source(JsonReader& w, const json& object, const fs::path& base_dir, const json& spec, int width_px,
                            int height_px) {
  allow_keys(w, object, {"file", "format", "region", "values", "row_order", "v_direction", "fit", "source", "eye"});
  WarpSource source;
  source.format = w.string("format", {"bourke", "pfm", "mpcdi"});
  source.file = base_dir / w.string("file");  // checked, made absolute and read by load_warp()
  const auto only_for = [&](const char* key, std::string_view formats) {
    if (w.has(key)) w.fail(key, cat("applies to \"format\": ", formats, " only (format is \"", source.format, "\")"));
  };
  if (source.format == "mpcdi") {
    source.region = w.string("region");
    if (source.region.empty()) w.fail("region", "= \"\": must name a region of the MPCDI file");
    source.eye = read_eye(w);
  } else {
    only_for("region", "\"mpcdi\"");
    only_for("eye", "\"mpcdi\"");
  }
  if (source.format == "bourke") only_for("values", "\"pfm\" and \"mpcdi\"");
  if (source.format != "bourke") only_for("fit", "\"bourke\"");
  if (source.format != "pfm") {
    only_for("row_order", "\"pfm\"");
    only_for("v_direction", "\"pfm\"");
  }
  if (w.string_or("values", "absolute", {"absolute", "offsets"}) == "offsets")
    source.conventions.values = WarpValues::offsets;
  if (w.string_or("row_order", "bottom_to_top", {"bottom_to_top", "top_to_bottom"}) == "top_to_bottom")
    source.row_order = PfmRowOrder::top_to_bottom;
  if (w.string_or("v_direction", "down", {"down", "up"}) == "up") source.conventions.v_direction = WarpVDirection::up;
  std::vector<std::string> fit_names;
  for (const MeshFit f : kMeshFits) fit_names.emplace_back(to_string(f));
  const std::string fit = w.string_or("fit", to_string(source.fit), fit_names);
  for (const MeshFit f : kMeshFits)
    if (fit == to_string(f)) source.fit = f;
  source.source_size_given = w.has("source");
  std::tie(source.source_width_px, source.source_height_px) = read_warp_source_size(w, spec, width_px, height_px);
  return source;
}

BlendSource read_blend(JsonReader& o, const fs::path& base_dir) {
  BlendSource blend;
  if (!o.has("blend")) return blend;
  const json& v = o.raw("blend");
  if (v.is_string()) {
    const std::string mode = o.string("blend", {"none", "auto", "mpcdi"});
    blend.mode = mode == "auto" ? BlendMode::automatic : mode == "mpcdi" ? BlendMode::mpcdi : BlendMode::none;
    return blend;
  }
  if (!v.is_object())
    o.fail("blend", cat("= ", brief(v),
                        ": must be \"none\", \"auto\", \"mpcdi\" or an object ({\"type\": \"auto\", ...}, "
                        "{\"file\": ..., \"gamma\": ...} or {\"type\": \"mpcdi\"})"));
  JsonReader b(v, o.file(), o.key_path("blend"));
  const std::string type = b.string_or("type", b.has("file") ? "file" : "auto", {"none", "auto", "file", "mpcdi"});
  if (type == "none") {
    allow_keys(b, v, {"type"});
  } else if (type == "mpcdi") {
    allow_keys(b, v, {"type"});
    blend.mode = BlendMode::mpcdi;  // the maps: use_region_maps()
  } else if (type == "auto") {
    allow_keys(b, v, {"type", "width_fraction"});
    blend.mode = BlendMode::automatic;
    blend.width_fraction = b.number_or("width_fraction", blend.width_fraction, kMinBlendWidthFraction,
                                       kMaxBlendWidthFraction, "of the smaller side");
  } else {
    allow_keys(b, v, {"type", "file", "gamma"});
    blend.mode = BlendMode::file;
    blend.file = b.existing_file("file", base_dir);
    blend.gamma = b.number_or("gamma", blend.gamma, kMinMaskGamma, kMaxMaskGamma);
  }
  return blend;
}

/// Blend "mpcdi" (given, or by default where the output's MPCDI region has an
/// alpha map): the region's maps into out.blend, checked. A ConfigError at
/// /outputs/<i>/blend for an output without an MPCDI warp, a region without an
/// alpha map or with a map zenith cannot apply (check_grey_blend_map), and at
/// .../black_level for a black_level given beside a beta map (β is the map's).
void use_region_maps(JsonReader& o, OutputConfig& out, const RegionMaps& maps) {
  const bool given = o.has("blend");
  if (!given && maps.alpha) out.blend.mode = BlendMode::mpcdi;
  if (out.blend.mode != BlendMode::mpcdi) return;
  const std::string value = given ? cat("= ", brief(o.raw("blend")), ": ") : std::string();
  if (!out.warp || out.warp->format != "mpcdi")
    o.fail("blend", cat(value, "output '", out.name,
                        "' has no MPCDI warp: blend \"mpcdi\" applies the alpha and beta maps of the MPCDI region its "
                        "\"warp\" names (docs/warp-meshes.md, \"Alpha and beta maps\")"));
  if (out.warp_error) return;  // the warp's own error stands for the output
  if (!maps.alpha)
    o.fail("blend", cat(value, "output '", out.name, "': region \"", out.warp->region, "\" of ", maps.source,
                        " has no alpha map (<alphaMap> in its <fileset>): choose \"none\", \"auto\" or a mask "
                        "file"));
  try {
    check_grey_blend_map(*maps.alpha, maps.source, out.warp->region, "alpha map");
    if (maps.beta) check_grey_blend_map(*maps.beta, maps.source, out.warp->region, "beta map");
  } catch (const std::runtime_error& e) {
    o.fail("blend", cat(value, "output '", out.name, "': ", e.what()));
  }
  if (maps.beta && o.has("black_level"))
    o.fail("black_level",
           cat("= ", brief(o.raw("black_level")), ": output '", out.name, "': region \"", out.warp->region, "\" of ",
               maps.source, " has a beta map, which gives β per pixel with blend \"mpcdi\"",
               given ? "" : " (the default for a region with an alpha map)",
               ": remove black_level, or give another \"blend\" to use black_level and not the "
               "region's maps (docs/warp-meshes.md, \"Alpha and beta maps\")"));
  out.blend.alpha_map = maps.alpha;
  out.blend.beta_map = maps.beta;
}

OutputConfig read_output(JsonReader& o, const fs::path& base_dir, const ViewportLoadOptions& options) {
  OutputConfig out;
  out.name = o.string("name");
  if (!valid_name(out.name))
    o.fail("name", cat("= \"", out.name, "\": must be 1 to ", kMaxNameLength,
                       " letters, digits, '-', '_' or '.' (it names the output's file)"));
  std::tie(out.width_px, out.height_px) = read_size(o);

  // An MPCDI region of the 3d, sl and a3 profiles gives the rays itself; any
  // other output needs its projection (checked once the warp is read).
  const bool mpcdi_warp = o.has("warp") && o.raw("warp").is_object() && o.raw("warp").contains("format") &&
                          o.raw("warp").at("format") == "mpcdi";
  const bool has_spec = o.has("projection") || !mpcdi_warp;
  const json spec = has_spec ? o.raw("projection") : json();
  if (has_spec && !spec.is_object())
    o.fail("projection", cat("must be an object (docs/projections.md), got ", brief(spec)));
  out.projection_spec = spec;

  RegionMaps maps;  // an MPCDI region's alpha and beta maps
  if (o.has("warp")) {
    const json& wv = o.raw("warp");
    if (!wv.is_object()) o.fail("warp", cat("must be an object {\"file\", \"format\", \"region\"}, got ", brief(wv)));
    JsonReader w(wv, o.file(), o.key_path("warp"));
    WarpSource source = read_warp_source(w, wv, base_dir, spec, out.width_px, out.height_px);
    // The base projection renders the warp's source image, at the source's
    // size. Made here first so that a bad spec fails the load even where the
    // warp file is broken.
    std::shared_ptr<const Projection> base =
        has_spec
            ? make_projection(spec, source.source_width_px, source.source_height_px, o.file(), o.key_path("projection"))
            : nullptr;
    try {
      LoadedWarp loaded = load_warp(w, source, base_dir, out.width_px, out.height_px);
      out.colour = loaded.colour;
      maps = loaded.maps;
      if (loaded.projection) {  // an MPCDI region that defines its rays
        if (has_spec)
          o.fail("projection", cat("the MPCDI region \"", source.region, "\" (profile ", loaded.profile,
                                   ") defines the output's rays (its frustum and frame, or its 3D warp): remove "
                                   "\"projection\" (docs/warp-meshes.md)"));
        out.projection = loaded.projection;
        out.projection_spec = mpcdi_source_projection_spec(*loaded.projection);
        // The image its warp addresses (the frustum's, a 3D warp's chart); the output's own without a warp.
        const auto* warped = dynamic_cast<const WarpedProjection*>(loaded.projection.get());
        source.source_width_px = warped ? warped->base().width() : out.width_px;
        source.source_height_px = warped ? warped->base().height() : out.height_px;
      } else {
        if (!has_spec)
          o.fail("projection", cat("missing: the MPCDI region \"", source.region, "\" (profile ", loaded.profile,
                                   ") maps the output into a source image; give the projection that renders it "
                                   "(docs/warp-meshes.md)"));
        // An MPCDI region's resolution is its image's size: the source, unless
        // the config's "source" says otherwise.
        if (loaded.source_size_px && !source.source_size_given &&
            *loaded.source_size_px != std::pair{source.source_width_px, source.source_height_px}) {
          std::tie(source.source_width_px, source.source_height_px) = *loaded.source_size_px;
          base = make_projection(spec, source.source_width_px, source.source_height_px, o.file(),
                                 o.key_path("projection"));
        }
        out.projection = std::make_shared<WarpedProjection>(out.width_px, out.height_px, std::move(*loaded.mesh), base);
      }
    } catch (const ConfigError&) {
      if (!options.keep_broken_warps) throw;
      out.warp_error = std::current_exception();  // out.projection stays null
    }
    out.warp = std::move(source);
  } else {
    out.projection = make_projection(spec, out.width_px, out.height_px, o.file(), o.key_path("projection"));
  }

  out.blend = read_blend(o, base_dir);
  out.black_level = o.number_or("black_level", 0.0, 0.0, kMaxBlackLevel, "(fraction of full white)");
  use_region_maps(o, out, maps);
  if (o.has("window")) out.window = read_output_window(o, "window", out.name);
  // The region's <encode> is the projector's response (VESA MPCDI v2.0
  // §2.5.1.3): a window encoding would describe it a second time.
  if (out.colour && out.window && out.window->gamma > 0.0)
    o.fail("window", cat("\"encoding\": {\"gamma\": ", out.window->gamma, "} with the MPCDI region \"",
                         out.warp->region, "\", whose <color> encodes for the projector (", describe(*out.colour),
                         "): remove the window's \"encoding\" (docs/warp-meshes.md, \"Colour profile\")"));
  return out;
}

}  // namespace

const char* to_string(BlendMode mode) {
  switch (mode) {
    case BlendMode::none: return "none";
    case BlendMode::automatic: return "auto";
    case BlendMode::file: return "file";
    case BlendMode::mpcdi: return "mpcdi";
  }
  return "?";
}

std::string describe_blend(const OutputConfig& output) {
  const BlendSource& b = output.blend;
  std::string text = to_string(b.mode);
  if (b.mode == BlendMode::mpcdi && b.alpha_map) {
    text += cat(" (region \"", output.warp ? output.warp->region : std::string(), "\": alpha map ",
                b.alpha_map->image.width, "x", b.alpha_map->image.height, " px, gammaEmbedded ",
                b.alpha_map->gamma_embedded);
    if (b.beta_map) text += cat("; beta map ", b.beta_map->image.width, "x", b.beta_map->image.height, " px");
    text += ")";
  }
  if (b.mode == BlendMode::mpcdi && b.beta_map) return text + "; black level: the beta map";
  return cat(text, "; black level ", output.black_level);
}

const OutputConfig* ViewportConfig::find(const std::string& output_name) const {
  for (const OutputConfig& o : outputs)
    if (o.name == output_name) return &o;
  return nullptr;
}

std::size_t ViewportConfig::largest_output_pixels() const {
  std::size_t largest = 0;
  for (const OutputConfig& o : outputs)
    largest = std::max(largest, static_cast<std::size_t>(o.width_px) * static_cast<std::size_t>(o.height_px));
  return largest;
}

std::size_t ViewportConfig::index_of(const std::string& output_name) const {
  for (std::size_t i = 0; i < outputs.size(); ++i)
    if (outputs[i].name == output_name) return i;
  std::string names;
  for (const OutputConfig& o : outputs) names += (names.empty() ? "" : ", ") + o.name;
  throw std::invalid_argument(cat(source, ": no output named '", output_name, "' (outputs: ", names, ")"));
}

void ViewportConfig::require_renderable(std::size_t index) const {
  const OutputConfig& output = outputs.at(index);
  if (output.warp_error) std::rethrow_exception(output.warp_error);
  if (output.blend.mode != BlendMode::automatic) return;
  for (std::size_t j = 0; j < outputs.size(); ++j) {
    const OutputConfig& other = outputs[j];
    if (j == index || other.blend.mode != BlendMode::automatic || !other.warp_error) continue;
    try {
      std::rethrow_exception(other.warp_error);
    } catch (const std::exception& e) {
      throw ConfigError(source, cat("/outputs/", index, "/blend"),
                        cat("output '", output.name, "' blends automatically with output '", other.name,
                            "', whose warp cannot be used, so its mask cannot be computed: ", e.what()));
    }
  }
}

ViewportConfig parse_viewport_config(const json& config, const std::string& source, const fs::path& base_dir,
                                     const ViewportLoadOptions& options) {
  JsonReader root(config, source);
  allow_keys(root, config, {"zenith_viewports", "name", "description", "outputs"});
  if (!root.has("zenith_viewports"))
    root.fail("zenith_viewports", cat("missing: a viewport config starts with \"zenith_viewports\": ",
                                      kViewportConfigVersion, " (the schema version)"));
  root.integer("zenith_viewports", kViewportConfigVersion, kViewportConfigVersion);

  ViewportConfig vc;
  vc.source = source;
  vc.name = root.string("name");
  if (vc.name.empty()) root.fail("name", "= \"\": must not be empty");
  vc.description = root.string_or("description", "", {});

  const json& outputs = root.raw("outputs");
  if (!outputs.is_array() || outputs.empty() || outputs.size() > static_cast<std::size_t>(kMaxOutputs))
    root.fail("outputs", cat("= ", brief(outputs), ": must be an array of 1 to ", kMaxOutputs, " outputs"));
  std::set<std::string> names;
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    const std::string pointer = cat("/outputs/", i);
    const json& ov = outputs[i];
    if (!ov.is_object()) throw ConfigError(source, pointer, cat("must be an object, got ", brief(ov)));
    JsonReader o(ov, source, pointer);
    allow_keys(o, ov, {"name", "size", "projection", "warp", "blend", "black_level", "window"});
    OutputConfig out = read_output(o, base_dir, options);
    if (!names.insert(out.name).second)
      o.fail("name", cat("= \"", out.name, "\": duplicate output name (names must be unique)"));
    vc.outputs.push_back(std::move(out));
  }
  return vc;
}

ViewportConfig load_viewport_config(const fs::path& path, const ViewportLoadOptions& options) {
  return parse_viewport_config(read_json_file(path), path.string(), path.parent_path(), options);
}

PlanarFrustum display_wall_frustum(const DisplayWall& wall, int column, int row) {
  if (wall.columns < 1 || wall.columns > 64 || wall.rows < 1 || wall.rows > 64)
    throw std::invalid_argument(
        cat("display wall: columns and rows must be in [1, 64], got ", wall.columns, " x ", wall.rows));
  if (column < 0 || column >= wall.columns || row < 0 || row >= wall.rows)
    throw std::invalid_argument(
        cat("display wall: screen (", column, ", ", row, ") outside ", wall.columns, " x ", wall.rows));
  if (!(wall.screen_width_mm > 0.0 && wall.screen_height_mm > 0.0 && wall.bezel_mm >= 0.0 && wall.distance_mm > 0.0 &&
        std::isfinite(wall.screen_width_mm) && std::isfinite(wall.screen_height_mm) && std::isfinite(wall.bezel_mm) &&
        std::isfinite(wall.distance_mm)))
    throw std::invalid_argument("display wall: screen sizes and distance must be finite and > 0, the bezel >= 0");
  const double gap_mm = 2.0 * wall.bezel_mm;
  const double total_w = wall.columns * wall.screen_width_mm + (wall.columns - 1) * gap_mm;
  const double total_h = wall.rows * wall.screen_height_mm + (wall.rows - 1) * gap_mm;
  const double x_left = -0.5 * total_w + column * (wall.screen_width_mm + gap_mm);
  const double y_top = 0.5 * total_h - row * (wall.screen_height_mm + gap_mm);
  const double d = wall.distance_mm;
  PlanarFrustum f{};
  f.left_deg = std::atan(x_left / d) * core::kRadToDeg;
  f.right_deg = std::atan((x_left + wall.screen_width_mm) / d) * core::kRadToDeg;
  f.up_deg = std::atan(y_top / d) * core::kRadToDeg;
  f.down_deg = std::atan((y_top - wall.screen_height_mm) / d) * core::kRadToDeg;
  return f;
}

}  // namespace zenith::warp
