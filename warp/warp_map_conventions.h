#pragma once
// How the (u, v) samples of a warp map (a plain PFM warp, an MPCDI geometry
// warp) are written. Tools disagree; docs/warp-meshes.md has the table of who
// writes what. zenith's own convention (WarpMesh) is (u, v) normalized in the
// source image with (0, 0) at its top-left, v down, absolute coordinates.
//
//  * Values: most writers store the absolute source position of each sample
//    (MPCDI as VESA defines it). Evans & Sutherland exports store the offset of
//    the source position from the sample's own place on the regular grid
//    instead, so that a map of zeros means "no distortion":
//        u = s_node + du,   v = v_node + dv,   s_node = i / (width − 1), v_node as below.
//  * V direction: v counted down from the top of the source image (zenith,
//    MPCDI), or up from its bottom (OpenGL texture coordinates: SGCT, E&S
//    surface files). With v up, the sample's own place on the grid is
//    v_node = 1 − j / (height − 1) (row j counted from the top), and
//    v_down = 1 − v_up.
//
// The order in which a PFM stores its rows is the third convention; it is the
// reader's (PfmRowOrder in warp/pfm.h), applied before these.
#include <string>

namespace zenith::warp {

/// What a warp map's (u, v) samples hold.
enum class WarpValues {
  absolute,  ///< the source position itself (MPCDI, SGCT, the default)
  offsets,   ///< the source position minus the sample's own place on the regular grid (E&S: zeros = identity)
};
/// "absolute", "offsets".
const char* to_string(WarpValues values);

/// The direction in which a warp map's v grows.
enum class WarpVDirection {
  down,  ///< v = 0 at the top of the source image (zenith, MPCDI, the default)
  up,    ///< v = 0 at the bottom (OpenGL texture coordinates: SGCT, E&S surface files)
};
/// "down", "up".
const char* to_string(WarpVDirection direction);

/// The conventions of one warp map's samples.
struct WarpMapConventions {
  WarpValues values = WarpValues::absolute;
  WarpVDirection v_direction = WarpVDirection::down;
};

/// A sample's source position in zenith's convention (absolute, v down) from
/// the stored (u, v) of the sample in column `column` of `columns` and row
/// `row` of `rows` (row 0 at the top, after the reader's row order): the
/// formulas above. Non-finite input stays non-finite.
struct WarpSourcePoint {
  double u, v;
};
WarpSourcePoint to_source_point(double stored_u, double stored_v, int column, int columns, int row, int rows,
                                const WarpMapConventions& conventions);

}  // namespace zenith::warp
