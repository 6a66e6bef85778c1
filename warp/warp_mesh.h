#pragma once
// A warp mesh: where each point of a projector's image takes its picture from.
// docs/warp-meshes.md has the file formats and the diagrams.
//
// Coordinates (both normalized, both with (0, 0) at the top-left, y down, like
// pixel coordinates in warp/projection.h):
//  * (s, t): a point of the projector's image, edge to edge: (0, 0) is the
//    top-left corner of its top-left pixel, (1, 1) the bottom-right corner of
//    its bottom-right pixel; s = x_px / width, t = y_px / height.
//  * (u, v): a point of the source image the projector shows (the dome master,
//    or the image rendered through a frustum), same convention.
//
// The mesh is a regular grid of columns × rows nodes spanning the rectangle
// [s_min, s_max] × [t_min, t_max] of the projector's image (normally [0, 1]²):
// node (i, j) sits at s = s_min + i / (columns − 1) · (s_max − s_min),
// t = t_min + j / (rows − 1) · (t_max − t_min), row j = 0 at the top. Each node
// carries (u, v), an intensity in [0, 1] (the projector's brightness there:
// the mesh's own edge blend) and whether it has data at all.
//
// Interpolation (sample()): a point takes its value from the grid cell it lies
// in; a cell with an invalid corner has no data (so the picture ends half a
// cell inside the last valid nodes rather than smearing into unknown areas).
//  * bilinear: between the cell's four corners;
//  * catmull_rom (default): the separable Catmull–Rom cubic over the 4 × 4 nodes
//    around the cell, which passes through the nodes, has a continuous first
//    derivative, and reproduces linear and quadratic maps exactly. Past the
//    mesh's border the missing outer nodes are extrapolated linearly (2·p0 − p1);
//    where any of the 16 nodes is invalid the cell falls back to bilinear.
// The interpolated intensity is clamped to [0, 1]; (u, v) is not clamped.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "warp/pfm.h"
#include "warp/warp_map_conventions.h"

namespace zenith::warp {

enum class WarpInterpolation {
  bilinear,     ///< C0; what a GPU drawing the mesh as textured quads gives (MPCDI "linear")
  catmull_rom,  ///< C1 interpolating cubic where the 4 × 4 neighbourhood is valid, bilinear elsewhere
};

/// One node of a WarpMesh.
struct WarpNode {
  double u = 0.0, v = 0.0;  ///< source position, normalized, (0, 0) top-left
  double intensity = 1.0;   ///< in [0, 1]
  bool valid = false;       ///< false: no data (NaN in a PFM, an unused Bourke node)
};

/// The rectangle of the projector's image a WarpMesh's node grid spans.
struct WarpExtent {
  double s_min = 0.0, s_max = 1.0, t_min = 0.0, t_max = 1.0;
};

class WarpMesh {
 public:
  struct Sample {
    double u, v;       ///< source position, normalized, (0, 0) top-left
    double intensity;  ///< in [0, 1]
  };
  using Extent = WarpExtent;

  /// `nodes` row by row from the top, columns × rows of them. Throws
  /// std::invalid_argument "<source>: ..." unless 2 ≤ columns, rows ≤ 16384,
  /// the node count matches, the extent is finite with s_min < s_max and
  /// t_min < t_max, and every valid node is finite with intensity in [0, 1];
  /// and "<source>: the warp mesh has no valid node (NaN-only mesh)" when none is valid.
  WarpMesh(int columns, int rows, std::vector<WarpNode> nodes, std::string source,
           WarpInterpolation interpolation = WarpInterpolation::catmull_rom, Extent extent = {});

  int columns() const { return columns_; }
  int rows() const { return rows_; }
  const WarpNode& node(int column, int row) const { return nodes_[static_cast<std::size_t>(row) * columns_ + column]; }
  const std::vector<WarpNode>& nodes() const { return nodes_; }
  const Extent& extent() const { return extent_; }
  WarpInterpolation interpolation() const { return interpolation_; }
  /// Where the mesh came from (a file name), for messages and describe().
  const std::string& source() const { return source_; }
  int valid_node_count() const { return valid_count_; }

  /// The interpolated node data at the projector point (s, t); nothing outside
  /// the mesh's extent, in a cell with an invalid corner, and for non-finite input.
  std::optional<Sample> sample(double s, double t) const;

 private:
  int columns_, rows_;
  std::vector<WarpNode> nodes_;
  std::string source_;
  WarpInterpolation interpolation_;
  Extent extent_;
  int valid_count_ = 0;
};

/// How a Bourke mesh meets a projector image of another aspect ratio (a 16:9
/// mesh at a 4:3 output). The mesh's frame is x ∈ [−a, a], y ∈ [−1, 1], a the
/// mesh's own aspect ratio (its largest |x|); the projector's aspect is A
/// (width / height, square pixels). Each fit shows the frame's part
/// x ∈ [−half_x, half_x], y ∈ [−half_y, half_y] across the projector's image,
/// centred (BourkeFrame):
enum class MeshFit {
  /// half = (A, 1): y ∈ [−1, 1] spans the image's height, x in the same units
  /// (what Bourke's tools and SGCT do): a wider mesh is cut off left and right,
  /// a narrower one leaves black bars left and right.
  height,
  /// half = (a, a / A): x ∈ [−a, a] spans the image's width, y in the same units:
  /// a wider mesh leaves black bars top and bottom, a narrower one is cut off
  /// top and bottom.
  width,
  /// The mesh fills the image keeping its shape, cut off where it overhangs:
  /// height for a wider mesh (a ≥ A), width for a narrower one.
  crop,
  /// The whole mesh is shown keeping its shape, black bars where it falls
  /// short: width for a wider mesh (a ≥ A), height for a narrower one.
  letterbox,
  /// half = (a, 1): the mesh's frame spans the image edge to edge both ways,
  /// squeezed or stretched across unless a = A.
  stretch,
};
/// "height", "width", "crop", "letterbox", "stretch".
const char* to_string(MeshFit fit);

/// The part of a Bourke mesh's (x, y) plane a projector image shows,
/// x ∈ [−half_x, half_x], y ∈ [−half_y, half_y]: s = (x + half_x) / (2 half_x),
/// t = (half_y − y) / (2 half_y).
struct BourkeFrame {
  double half_x = 1.0, half_y = 1.0;
};
/// The frame of `fit` for a mesh of aspect ratio mesh_aspect shown on a
/// projector image of aspect ratio output_aspect (both width / height, > 0).
BourkeFrame bourke_frame(MeshFit fit, double mesh_aspect, double output_aspect);

/// Options of load_bourke_mesh().
struct BourkeMeshOptions {
  /// The projector's aspect ratio (width / height), in (0, 100]. Unset: the
  /// mesh's own (its largest |x|), and then every fit is the same.
  std::optional<double> aspect;
  /// How the mesh meets a projector of another aspect ratio; height, as
  /// Bourke's tools and SGCT show it, unless told.
  MeshFit fit = MeshFit::height;
  /// Nodes per side of the regular grid a mesh whose x, y positions do not form
  /// one is resampled onto, in [2, 4096]; unset: 4 · (n − 1) + 1 per side, at most 1025.
  std::optional<int> resample_columns, resample_rows;
};

/// Reads a Paul Bourke warp mesh (".data", ASCII, mesh type 2 = rectangular):
///
///   line 1: the mesh type                  (2; 1 = polar is not supported)
///   line 2: nx ny                          (nodes per row, rows; each in [2, 16384])
///   then nx · ny lines "x y u v intensity", rows from the bottom, left to right in a row
///
/// x, y: the node's position in the projector's image, x ∈ [−aspect, aspect] to
/// the right, y ∈ [−1, 1] up (shown through options.fit's frame, BourkeFrame); u, v: its texture coordinate in the
/// source image, [0, 1], v up; intensity in [0, 1] (values a little above 1 are clamped). A node with u or v outside
/// [0, 1], a negative intensity or a non-finite u, v or intensity is unused. Blank lines and CR LF line ends are
/// accepted.
///
/// The warp may sit in the (u, v) (x, y a regular grid: used as it is) or in the
/// (x, y) positions (then resampled onto a regular grid by inverting the
/// bilinear map of every quad with four used nodes, first quad wins where the
/// mesh folds over itself).
///
/// Throws std::runtime_error "<path>:<line>: <what>" naming the field for a bad
/// type or size line, a node line without exactly 5 fields, a field that is not
/// a number ("field 'u' = 'abc' is not a number") and a non-finite x or y;
/// "<path>:<line>: more than nx·ny nodes" (wrong counts) and
/// "<path>: truncated: ..." for fewer; and the WarpMesh errors (no used node).
WarpMesh load_bourke_mesh(const std::filesystem::path& path, const BourkeMeshOptions& options = {});

/// A warp mesh from a 3-channel PFM (e.g. an MPCDI geometry warp, or a plain
/// PFM warp map): pixel (i, j) of `map` (row 0 at the top) is node (i, j), the
/// nodes spanning the projector's image edge to edge; channels 0 and 1 are the
/// stored (u, v), turned into zenith's convention by `conventions` (absolute
/// values or offsets from the regular grid, v down or up:
/// warp/warp_map_conventions.h); channel 2 is ignored; a node with a non-finite
/// u or v has no data. Intensity 1 everywhere. Logs the warnings of
/// warp_map_warnings() (spdlog, level warn): a map that collapses to one
/// point, looks like offsets read as absolute values, or maps most samples
/// outside the source image. Throws std::invalid_argument "<source>: ..." for a
/// 1-channel map, a map narrower or lower than 2, and a map without any finite node.
WarpMesh warp_mesh_from_pfm(const PfmImage& map, const std::string& source,
                            WarpInterpolation interpolation = WarpInterpolation::catmull_rom,
                            const WarpMapConventions& conventions = {});

/// read_pfm(path, stored_rows) then warp_mesh_from_pfm(). Plain PFM warp maps
/// follow the classic PFM row order (first stored row = the bottom), absolute
/// values and v down unless told otherwise; SGCT and E&S surface files store
/// the top row first with v up (docs/warp-meshes.md has the table).
WarpMesh load_pfm_warp_mesh(const std::filesystem::path& path, PfmRowOrder stored_rows = PfmRowOrder::bottom_to_top,
                            WarpInterpolation interpolation = WarpInterpolation::catmull_rom,
                            const WarpMapConventions& conventions = {});

}  // namespace zenith::warp
