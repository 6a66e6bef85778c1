#pragma once
// Writing MPCDI archives (VESA Multiple Projector Common Data Interchange) for
// projectors and media servers that warp and blend themselves: one output
// becomes one archive of the "2d" profile holding one buffer with one region
// that spans it, and that region's geometry warp (PFM), alpha map and beta map
// (16-bit grey PNG); or, for an output whose projection is a pinhole (planar),
// one of the "sl" profile (below). What load_mpcdi() (warp/mpcdi.h) reads back:
//
//   <MPCDI profile="2d" geometry="1" color="1" version="2.0">
//     <display>
//       <buffer id="ID" xResolution="W" yResolution="H">
//         <region id="ID" x="0" y="0" xsize="1" ysize="1" xResolution="W" yResolution="H">
//           <color> decode gamma 2.2, correct none, encode gamma 2.2 </color>     (colour_gamma)
//         </region>
//       </buffer>
//     </display>
//     <files>
//       <fileset region="ID">
//         <geometryWarpFile> path, interpolation, componentDepth 2, bitDepth 32, xSamples, ySamples,
//                            originOf2DData topLeftCorner </geometryWarpFile>
//         <alphaMap> path, componentDepth 1, bitDepth 16, gammaEmbedded </alphaMap>
//         <betaMap> path, componentDepth 1, bitDepth 16 </betaMap>
//       </fileset>
//     </files>
//   </MPCDI>
//
// The geometry warp's samples start top-left and hold absolute (x, y)
// normalized in the region's source image, (0, 0) its top-left, y down; NaN =
// no data (docs/warp-meshes.md, "MPCDI").
//
// The sl profile (shader lamps: the projector a pinhole aimed at the screen):
//
//   <MPCDI profile="sl" geometry="1|2" color="2" version="2.0">
//     ... <region ...>
//           <frustum> yaw pitch roll rightAngle leftAngle upAngle downAngle </frustum>
//           <coordinateFrame> pos 0; yaw (0, −1, 0), pitch (−1, 0, 0), roll (0, 0, 1) </coordinateFrame>
//         </region> ...
//       <fileset region="ID">
//         <distortionMap> path </distortionMap>          the warp, when the output has one
//         <alphaMap> ... </alphaMap> <betaMap> ... </betaMap>
//       </fileset>
//
// The coordinate frame is the projector's base axes in the display's frame
// (X left, Y up, Z forward), so the frustum's yaw, pitch and roll are the
// output's own (warp/mpcdi_projection.h: F = I). No <geometryWarpFile>: zenith
// has no 3D model of the screen; the archive says what the renderer shows.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "warp/mpcdi.h"
#include "warp/planar_projection.h"
#include "warp/warp_mesh.h"

namespace zenith::warp {

/// The one region of an exported 2d-profile archive and the members holding its maps.
struct MpcdiRegionExport {
  std::string id;  ///< the buffer's and the region's id: letters, digits, '-', '_', '.'
  /// The region's resolution: the size of the region's image, the source the
  /// warp's (x, y) address (zenith reads it back as the warp's source size).
  int width_px = 0, height_px = 0;
  std::string warp_member;  ///< the geometry warp PFM (3 channels, top row first)
  int warp_columns = 0, warp_rows = 0;
  WarpInterpolation interpolation = WarpInterpolation::bilinear;  ///< "linear" or "cubic"
  std::string alpha_member;                                       ///< 16-bit grey PNG
  double alpha_gamma_embedded = 1.0;  ///< the alpha map's blend weight in linear light is value^gamma
  std::string beta_member;            ///< 16-bit grey PNG
  /// media_2d (the default) or shader_lamps: a pinhole projector, `frustum`
  /// in the base coordinate frame; the warp member, when not empty, is its
  /// lens <distortionMap> (a 2D warp of the frustum's image).
  MpcdiProfile profile = MpcdiProfile::media_2d;
  /// sl: the frustum, in zenith's camera frame (PlanarProjection::frustum()).
  PlanarFrustum frustum{-1.0, 1.0, -1.0, 1.0};
  /// The region's <color>: decode and encode this gamma, correct none. 2.2:
  /// the signal zenith renders is sRGB, which a media player decodes as about
  /// 2.2, and §2.5.1.3 asks for the decode's gamma where the display's own
  /// response is not characterized. In [kMinColourGamma, kMaxColourGamma].
  double colour_gamma = 2.2;
};

/// The mpcdi.xml text describing `region` (the layouts above). Throws
/// std::invalid_argument for an id with other characters (it is written into
/// XML attributes unescaped), a resolution or warp size below 1, an empty
/// member name (the warp's may be empty for sl: no distortion map), or a
/// profile other than 2d and sl.
std::string mpcdi_descriptor(const MpcdiRegionExport& region);

/// Writes a ZIP archive at `path` holding "mpcdi.xml" = `descriptor` and, for
/// each (member, file), the file's bytes under that member name. libzip writes
/// a temporary file next to `path` and renames it on success, so a failed write
/// leaves no archive. Throws std::runtime_error "<path>: <libzip's reason>"
/// when the archive cannot be created or written, or a file cannot be read.
void write_mpcdi_archive(const std::filesystem::path& path, const std::string& descriptor,
                         const std::vector<std::pair<std::string, std::filesystem::path>>& members);

}  // namespace zenith::warp
