#pragma once
// The viewport/output part of a cluster configuration: what each output (a
// projector, a screen of a display wall, a dome master) shows, at what size,
// through which projection and warp, with which blend mask and black level.
// docs/viewports.md has the schema, the blend model and the bezel arithmetic.
//
//   {
//     "zenith_viewports": 1,
//     "name": "dome-6",
//     "outputs": [
//       {"name": "p1", "size": [1920, 1200],
//        "projection": {"type": "planar", "left_deg": -45, ...},          make_projection() spec
//        "warp": {"file": "p1.data", "format": "bourke",                  optional; bourke "fit", pfm and
//                 "source": {"size_px": [1080, 1080]}},                   mpcdi "values", pfm "row_order",
//                 "v_direction"
//        "blend": "auto",                                                 "none" | "auto" | "mpcdi" | object
//        "black_level": 0.02}                                             β in [0, 0.5]
//     ]
//   }
//
// Keys are strict; every error is a zenith::ConfigError naming the file, the
// JSON pointer of the key, the value and the allowed range, e.g.
//   dome.json: /outputs/2/black_level = 0.8: must be in [0, 0.5]
#include <cstddef>
#include <exception>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include "warp/colour_profile.h"
#include "warp/output_window.h"
#include "warp/pfm.h"
#include "warp/planar_projection.h"
#include "warp/projection.h"
#include "warp/warp_map_conventions.h"
#include "warp/warp_mesh.h"

namespace zenith::warp {

struct MpcdiBlendMap;  // warp/mpcdi.h

/// The schema version this reader understands ("zenith_viewports": 1).
inline constexpr int kViewportConfigVersion = 1;

enum class BlendMode {
  none,       ///< α = 1 everywhere (a dome master, non-overlapping screens)
  automatic,  ///< α from the overlap of the outputs' coverage (warp/blending.h)
  file,       ///< α read from a PNG mask
  mpcdi,      ///< α (and β) from the MPCDI region's alpha (and beta) map (warp/mpcdi_blend.h)
};
/// "none", "auto", "file", "mpcdi".
const char* to_string(BlendMode mode);

/// Where an output's blend mask α comes from. α is a weight in linear light.
struct BlendSource {
  BlendMode mode = BlendMode::none;
  /// automatic: the ramp width as a fraction of the output's smaller side, in
  /// (0, 0.5]; a pixel this far (or farther) inside the border of the output's
  /// coverage has its full raw weight.
  double width_fraction = 0.1;
  /// file: the PNG (8 or 16 bit, grey or RGB: channel 0 is used), resolved
  /// against the config's folder; its size must be the output's.
  std::filesystem::path file;
  /// file: α = stored^gamma, stored = integer / (2^bits − 1) (MPCDI's
  /// gammaEmbedded); in [0.1, 10], 1 (linear) unless given.
  double gamma = 1.0;
  /// mpcdi: the alpha map of the output's MPCDI region (α), and its beta map
  /// (β per pixel) or null (β is then OutputConfig::black_level). Null only
  /// where the warp could not be loaded (OutputConfig::warp_error).
  std::shared_ptr<const MpcdiBlendMap> alpha_map, beta_map;
};

/// The warp file of an output, as configured (the mesh is already built into
/// OutputConfig::projection).
struct WarpSource {
  std::filesystem::path file;  ///< resolved against the config's folder
  std::string format;          ///< "bourke", "pfm" or "mpcdi"
  std::string region;          ///< mpcdi: the region id; empty otherwise
  /// pfm: "row_order", the order the file stores its rows in; default
  /// bottom_to_top (the classic PFM; SGCT and E&S surface files: top_to_bottom).
  PfmRowOrder row_order = PfmRowOrder::bottom_to_top;
  /// pfm: "values" and "v_direction" (defaults absolute, down); mpcdi: "values"
  /// (MPCDI fixes v down). warp/warp_map_conventions.h has the formulas.
  WarpMapConventions conventions;
  /// bourke: "fit", how a mesh made for another aspect ratio meets the output
  /// (a 16:9 mesh at a 4:3 output): "height" (the default: y spans the
  /// output's height, x in the same units, as Bourke's tools and SGCT do),
  /// "width", "crop", "letterbox", "stretch" (warp/warp_mesh.h, MeshFit).
  MeshFit fit = MeshFit::height;
  /// "source": the size of the source image the mesh's (u, v) address (the
  /// output's "projection" renders it at this size), {"size_px": [w, h]}
  /// (each in [1, 16384]) or {"aspect": a} (a in [0.1, 10]: the output's
  /// height, a · height wide). Default: for MPCDI the region's xResolution ×
  /// yResolution (the region's image, which its warp addresses); else square,
  /// side = the output's height, for a "fisheye" projection (a dome master, as
  /// Bourke meshes and the spherical-mirror setup mean it); the output's size
  /// for any other.
  int source_width_px = 0, source_height_px = 0;
  /// Whether the config gave "source" (which then wins over the MPCDI region's resolution).
  bool source_size_given = false;
  /// mpcdi: "eye", [x, y, z]: the origin of the rays of a region's 3D geometry
  /// warp, in the file's 3D frame and unit; unset: the 3D data's origin where
  /// the file says it is the ideal eye point (warp/mpcdi_projection.h).
  std::optional<glm::dvec3> eye;
};

struct OutputConfig {
  std::string name;  ///< unique in its config; letters, digits, '-', '_', '.' (a file name)
  int width_px = 0, height_px = 0;
  /// The "projection" object as given. For an MPCDI region of the 3d, sl or
  /// a3 profile, which defines the rays itself (the config gives no
  /// "projection"), the object of the projection its warp addresses
  /// (mpcdi_source_projection_spec(): the frustum's planar, or a 3D warp's chart).
  nlohmann::json projection_spec;
  /// The output's rays: make_projection(projection_spec, size) or, with a warp,
  /// a WarpedProjection of the output's size over make_projection(projection_spec,
  /// the warp's source size) (WarpSource::source_width_px: by default the
  /// MPCDI region's resolution, square for a fisheye, the output's size otherwise).
  std::shared_ptr<const Projection> projection;
  std::optional<WarpSource> warp;
  /// "blend": as given; absent, "mpcdi" for an output whose MPCDI region has
  /// an alpha map (the file's calibration), "none" otherwise.
  BlendSource blend;
  /// β: the projector's black level as a fraction of its full white, in
  /// [0, 0.5]; the output stage writes P·α·(1 − β) + β (docs/viewports.md).
  /// With blend "mpcdi" and a region's beta map, β is the map's per pixel
  /// (BlendSource::beta_map; the config may then not give black_level) and this is 0.
  double black_level = 0.0;
  /// The MPCDI region's colour profile (its <color>: decode, correct, encode;
  /// warp/colour_profile.h), null for any other output and a region without
  /// one. The output stage then runs processPixel on zenith's signal, with
  /// `blend`'s α and β (the region's maps with blend "mpcdi") or `black_level`
  /// as β (docs/warp-meshes.md, "Colour profile").
  std::shared_ptr<const MpcdiColourProfile> colour;
  /// Where a render node shows the output ("window": warp/output_window.h);
  /// unset: in the node's default window, beside its other such outputs.
  std::optional<OutputWindow> window;
  /// Only with ViewportLoadOptions::keep_broken_warps: why the warp cannot be
  /// used (the ConfigError a strict load throws, e.g. ".../warp/file: cannot
  /// use the warp: p2.pfm: PFM: truncated ..."); projection is then null.
  std::exception_ptr warp_error;
};

struct ViewportConfig {
  std::string name;
  std::string description;  ///< optional, "" when absent
  std::string source;       ///< the file it came from (messages)
  std::vector<OutputConfig> outputs;

  /// The output with that name; nullptr when none.
  const OutputConfig* find(const std::string& output_name) const;
  /// Its index in outputs; throws std::invalid_argument listing the names when none.
  std::size_t index_of(const std::string& output_name) const;
  /// The pixels (width × height) of its largest output; 0 without outputs.
  std::size_t largest_output_pixels() const;
  /// Throws what stops output `index` from being rendered: its own warp_error,
  /// or, when it blends automatically, a ConfigError at /outputs/<index>/blend
  /// naming the automatically blended output whose warp is broken (its
  /// coverage shapes this output's mask) and that output's error. Returns for
  /// a renderable output (always, for a config loaded strictly).
  void require_renderable(std::size_t index) const;
};

/// An output's blend and black level for logs and image attributes: "auto;
/// black level 0.02", or with an MPCDI region's maps "mpcdi (region "left":
/// alpha map 4x3 px, gammaEmbedded 2.2; beta map 4x3 px); black level: the beta map".
std::string describe_blend(const OutputConfig& output);

/// Options of parse_viewport_config() and load_viewport_config().
struct ViewportLoadOptions {
  /// false (the default): a warp that cannot be used (a missing or broken
  /// file, an unknown MPCDI region) fails the whole config. true: the error is
  /// kept in its output (OutputConfig::warp_error, projection null) and the
  /// other outputs load, so that one broken output does not stop another
  /// (`zenith render --viewport FILE#good`); ViewportConfig::require_renderable()
  /// gives the error when the broken output is asked for. Errors in the config's
  /// own keys and values fail the load either way.
  bool keep_broken_warps = false;
};

/// Parses a viewport config held in `config`. `source` names the file in
/// messages; relative warp and blend files resolve against `base_dir`.
/// Throws zenith::ConfigError for anything invalid: a missing or wrong version,
/// unknown keys, a bad size, projection, warp, blend or black level, duplicate
/// or invalid names, a missing warp or blend file, and a warp file that cannot
/// be read (its loader's message, pointing at /outputs/<i>/warp/file; kept in
/// the output instead with options.keep_broken_warps).
ViewportConfig parse_viewport_config(const nlohmann::json& config, const std::string& source,
                                     const std::filesystem::path& base_dir, const ViewportLoadOptions& options = {});
/// Reads and parses a file (ConfigError "cannot open file" when unreadable).
ViewportConfig load_viewport_config(const std::filesystem::path& path, const ViewportLoadOptions& options = {});

// ---------------------------------------------------------------------------
// Display walls with bezel compensation.

/// A flat wall of identical screens seen from a point on the normal through the
/// wall's centre. Lengths in millimetres.
struct DisplayWall {
  int columns = 3, rows = 2;      ///< each in [1, 64]
  double screen_width_mm = 0.0;   ///< the active (lit) area of one screen, > 0
  double screen_height_mm = 0.0;  ///< > 0
  double bezel_mm = 0.0;     ///< the frame on each side of a screen, ≥ 0: adjacent pictures are 2 · bezel_mm apart
  double distance_mm = 0.0;  ///< from the eye to the wall, > 0
};

/// The asymmetric frustum of the screen in `column` (0 = left) and `row`
/// (0 = top), all axes straight ahead (the wall is one plane z = −distance):
///   W = columns · w + (columns − 1) · 2b,     x_left = −W / 2 + column · (w + 2b)
///   H = rows · h + (rows − 1) · 2b,           y_top  =  H / 2 − row · (h + 2b)
///   left = atan(x_left / D), right = atan((x_left + w) / D),
///   up = atan(y_top / D),    down = atan((y_top − h) / D)
/// so the picture continues behind the bezels (the hidden part is not shown)
/// and a straight line crossing two screens stays straight. Throws
/// std::invalid_argument for parameters out of range.
PlanarFrustum display_wall_frustum(const DisplayWall& wall, int column, int row);

}  // namespace zenith::warp
