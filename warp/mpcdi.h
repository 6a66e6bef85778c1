#pragma once
// MPCDI (VESA Multiple Projector Common Data Interchange, v1 and v2) files: a
// ZIP archive holding mpcdi.xml and the warp and blend files it names
// (vendors also write mpacs.xml, or a single differently named .xml).
// docs/warp-meshes.md describes what is read and how.
//
//   <MPCDI profile="2d|3d|a3|sl" geometry=".." version="2.0">
//     <display>
//       <buffer id=".." xResolution=".." yResolution="..">
//         <region id=".." x=".." y=".." xsize=".." ysize=".." xResolution=".." yResolution="..">
//           <frustum> yaw pitch roll leftAngle rightAngle upAngle downAngle (degrees) </frustum>
//           <coordinateFrame> posx posy posz yawx yawy yawz pitchx pitchy pitchz rollx rolly rollz </coordinateFrame>
//           <color> <decode type gamma/> <correct type> <primaries>..</primaries> </correct> <encode type gamma/>
//           </color>
//         </region> ...
//       </buffer> ...
//     </display>
//     <files>
//       <fileset region="..">
//         <geometryWarpFile> path interpolation componentDepth geometricUnit originOf3DData </geometryWarpFile>
//         <alphaMap> path componentDepth bitDepth gammaEmbedded </alphaMap>
//         <betaMap> path componentDepth bitDepth </betaMap>
//         <distortionMap> path </distortionMap>                          (sl)
//         <decodeLUT>, <correctLUT>, <encodeLUT> path interpolation     (.cube, §3.8)
//       </fileset> ...
//     </files>
//   </MPCDI>
//
// Element and attribute names are matched ignoring case; unknown elements
// (extensionSet, ...) are skipped, and so is a <coordinateFrame> of
// the 2d and a3 profiles, which have none (VESA MPCDI v2.0 §3.5.2).
//
// Geometry warps are PFMs whose samples start top-left and span the region's
// raster edge to edge, in either byte order, NaN = no data. For the 2d and 3d
// profiles each sample holds (x, y) normalized in the region's image ((0, 0) its
// top-left; for 3d the image rendered through the region's frustum), which is
// what a WarpMesh holds: the region gets one. For a3 and sl (and a 3d warp
// that says it holds 3D data: componentDepth 3, a geometricUnit or an
// originOf3DData, as media servers write) the samples are 3D points on the
// screen, which need the viewer's position to become rays: the map is kept,
// and warp/mpcdi_projection.h makes the rays. An sl region's <distortionMap>
// (the projector lens's 2D LUT, the format of a 2D warp) gets a WarpMesh.
//
// A region's <color> and its fileset's .cube LUTs are its colour profile
// (warp/colour_profile.h, read by warp/mpcdi_colour.h), for every profile; a
// region without <color> has none: the identity, zenith's own output stage.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "warp/blend_map.h"
#include "warp/colour_profile.h"
#include "warp/pfm.h"
#include "warp/planar_projection.h"
#include "warp/warp_map_conventions.h"
#include "warp/warp_mesh.h"

namespace zenith::warp {

enum class MpcdiProfile {
  media_2d,       ///< "2d": 2D media
  simulation_3d,  ///< "3d": 3D simulation (a frustum per region)
  advanced_3d,    ///< "a3": advanced 3D (warps to 3D points)
  shader_lamps,   ///< "sl": shader lamps (warps to 3D points)
};
/// "2d", "3d", "a3", "sl".
const char* to_string(MpcdiProfile profile);

/// A region's view frustum, angles in degrees, MPCDI's conventions: yaw turns
/// right, pitch up, roll raises the left wing; leftAngle and downAngle are
/// normally negative. These are PlanarFrustum's conventions, so planar() copies.
/// Yaw, pitch and roll are read in [−360, 360] (vendors write [0, 360) as often
/// as (−180, 180]) and kept normalized (warp/orientation_angles.h): yaw and roll
/// in (−180, 180], pitch in [−90, 90], the same rotation.
struct MpcdiFrustum {
  double yaw_deg = 0, pitch_deg = 0, roll_deg = 0;
  double left_deg = 0, right_deg = 0, up_deg = 0, down_deg = 0;
  int line = 0;  ///< of <frustum> in the descriptor (messages)

  PlanarFrustum planar() const { return {left_deg, right_deg, down_deg, up_deg, yaw_deg, pitch_deg, roll_deg}; }
};

/// A region's <coordinateFrame> (VESA MPCDI v2.0 §2.2.2): the projector's
/// position and the unit vectors of its pitch, yaw and roll axes (figure 2-2:
/// pitch along the right wing, yaw down, roll forward; the axes positive
/// angles turn about, right-handed), in the display's 3D frame. Read for the
/// 3d and sl profiles; the axes are checked orthonormal and right-handed
/// (pitch × yaw = roll) within 1e-3. docs/warp-meshes.md, "Frustum and frame".
struct MpcdiCoordinateFrame {
  glm::dvec3 position{0.0};
  glm::dvec3 yaw_axis{0.0}, pitch_axis{0.0}, roll_axis{0.0};
  int line = 0;  ///< of <coordinateFrame> in the descriptor (messages)
};

struct MpcdiGeometryWarp {
  std::string path;           ///< the member of the archive
  std::string interpolation;  ///< as written ("linear"); linear, unknown → bilinear; cubic, smooth → Catmull–Rom
  WarpInterpolation mesh_interpolation = WarpInterpolation::bilinear;  ///< what `interpolation` asks for
  int component_depth = 2;                                             ///< 2 (x, y) or 3 (x, y, z)
  PfmImage map;                                                        ///< row 0 at the top
  /// The samples are 3D points of the screen (x, y, z) in the display's frame
  /// (a3, sl; 3d when the file says so), not 2D positions.
  bool points_3d = false;
  std::string geometric_unit = "unknown";     ///< <geometricUnit>: mm, cm, dm, m, in, ft, yd or unknown
  std::string origin_of_3d_data = "unknown";  ///< <originOf3DData>: centerOfMass, idealEyePoint, floorCenter or unknown
  int line = 0;                               ///< of the element in the descriptor (messages)
};

/// An alpha (blend) or beta (black-level) map. Values are the stored ones
/// (BlendMap: integer / (2^bits − 1)); an alpha map's blend weight in linear
/// light is value^gamma_embedded. The loader checks what VESA MPCDI v2.0 §3.7
/// and §3.6.1 constrain: at least 2 × 2 px, and a declared componentDepth and
/// bitDepth that the PNG has. warp/mpcdi_blend.h maps it onto an output's pixels.
struct MpcdiBlendMap {
  std::string path;             ///< the member of the archive
  int component_depth = 1;      ///< as declared (1 or 3; the image's channel count when absent)
  int bit_depth = 8;            ///< as declared (8 or 16; the image's when absent)
  double gamma_embedded = 1.0;  ///< alpha maps: <gammaEmbedded>, 1 when absent; beta maps: 1
  BlendMap image;
  int line = 0;  ///< of <alphaMap> or <betaMap> in the descriptor (messages)

  /// value^gamma_embedded of channel c (channel 0 for a 1-channel image).
  double linear(int x, int y, int c = 0) const;
};

struct MpcdiRegion {
  std::string id;
  int line = 0;                               ///< of <region> in the descriptor (messages)
  double x = 0, y = 0, xsize = 1, ysize = 1;  ///< the region in its buffer, normalized, (0, 0) top-left
  int x_resolution_px = 0, y_resolution_px = 0;
  std::optional<MpcdiFrustum> frustum;                   ///< required for the 3d and sl profiles
  std::optional<MpcdiCoordinateFrame> coordinate_frame;  ///< required for sl, optional for 3d
  std::optional<MpcdiGeometryWarp> geometry_warp;
  std::optional<WarpMesh> warp_mesh;  ///< from a geometry_warp of 2D positions (profiles 2d and 3d)
  /// sl: the lens distortion LUT (<distortionMap>), 2D positions in the image
  /// of the region's pinhole (frustum), the format of a 2D warp; and its mesh.
  std::optional<MpcdiGeometryWarp> distortion_map;
  std::optional<WarpMesh> distortion_mesh;
  std::optional<MpcdiBlendMap> alpha_map, beta_map;
  /// <color> with its LUTs (VESA MPCDI v2.0 §2.5); nothing when the region has
  /// no <color>: the output stage is zenith's own (docs/warp-meshes.md, "Colour profile").
  std::optional<MpcdiColourProfile> colour;
};

struct MpcdiBuffer {
  std::string id;
  int x_resolution_px = 0, y_resolution_px = 0;  ///< 0 when not given
  std::vector<MpcdiRegion> regions;
};

struct MpcdiFile {
  std::string path;        ///< the archive (as given)
  std::string descriptor;  ///< the member read as mpcdi.xml (also mpacs.xml, or the only .xml member)
  MpcdiProfile profile = MpcdiProfile::media_2d;
  std::string version;   ///< as written, "" when absent
  int colour_level = 0;  ///< <MPCDI color=".."> in [1, 5] (table 3-3); 0 when absent or not a number (then not checked)
  std::vector<MpcdiBuffer> buffers;

  /// The region with that id (ids are unique across buffers); nullptr when none.
  const MpcdiRegion* find_region(const std::string& id) const;
};

/// Options of load_mpcdi().
struct MpcdiLoadOptions {
  /// What the geometry warps of the 2d and 3d profiles hold: absolute positions
  /// in the region's image (VESA MPCDI) or offsets from each sample's place on
  /// the regular grid (Evans & Sutherland exports: all zeros = no distortion).
  WarpValues warp_values = WarpValues::absolute;
};

/// Reads an .mpcdi archive. The descriptor is mpcdi.xml (matched ignoring case,
/// in any folder of the archive, the shallowest), else mpacs.xml, else the
/// archive's only .xml member (older E&S exports). A <geometryWarpFile>,
/// <alphaMap> or <betaMap> that names no file (`<alphaMap />`, an empty <path>)
/// is ignored with a warning (spdlog). Throws std::runtime_error naming the
/// archive, the member and the line of the descriptor where it applies, e.g.
/// "show.mpcdi:mpcdi.xml:7: <region> has no attribute 'xsize'", for: an archive
/// that cannot be opened or is not a ZIP (one that starts like a ZIP: "may be
/// truncated"); no descriptor (the message lists the archive's members); malformed XML;
/// a frustum's yaw, pitch or roll outside [−360, 360], an edge angle outside
/// (−90, 90) or left ≥ right, down ≥ up; a coordinate frame whose axes are not
/// orthonormal and right-handed; a missing required attribute or element
/// (a frustum for 3d and sl, a coordinate frame for sl), or a value out of range;
/// an unknown profile, geometricUnit or originOf3DData; a duplicate region id;
/// a fileset naming an unknown region; a warp or blend file missing from the
/// archive; a broken PFM (truncated, bad header) or PNG; an alpha or beta map
/// smaller than 2 × 2 px or whose PNG has another channel count or bit depth
/// than its componentDepth or bitDepth declare; a <color> or .cube LUT
/// that warp/mpcdi_colour.h and warp/cube_lut.h refuse; and a NaN-only warp
/// (std::invalid_argument from WarpMesh, message "<archive>:<member>: ... NaN-only mesh").
MpcdiFile load_mpcdi(const std::filesystem::path& path, const MpcdiLoadOptions& options = {});

}  // namespace zenith::warp
