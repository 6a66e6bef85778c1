#pragma once
// The rays of an MPCDI region of the 3d, sl and a3 profiles, which its file
// defines itself (a 2d region's warp addresses a source image whose projection
// the viewport config gives). docs/warp-meshes.md, "Frustum and frame", has
// the conventions with a worked example.
//
// Frames (VESA MPCDI v2.0 §2.2, §2.2.1, §2.2.2, §3.6.3):
//  * S, the viewer frame of the standard: X right, Y down, Z forward; yaw
//    turns right about +Y, pitch up about +X, roll clockwise (as the viewer
//    sees it) about +Z, each a right-handed turn by a positive angle.
//  * The display's 3D frame ("world"): that of <coordinateFrame> and of 3D
//    geometry warps; right-handed, and the standard prefers X left, Y up,
//    Z forward (into the screen). zenith reads it so: the camera frame (x
//    right, y up, −z forward) is W · world, W = diag(−1, 1, −1); the dome's
//    zenith is the world's +Y.
//  * A coordinate frame gives, in the world, the unit vectors of the
//    projector's pitch (right), yaw (down) and roll (forward) axes: the
//    columns of B = [pitch | yaw | roll], the viewer frame S → world.
//
// A ray of the frustum (tangents (x, y) in S, y down, Z = 1) reaches the
// camera frame through the frustum's own rotation, yaw first, then pitch, then
// roll (§2.2: "Yaw shall always be done first, followed by pitch, followed by
// roll"; §2.2.1's Roll × Pitch × Yaw acts on row vectors, its OpenGL example
// on column vectors Ry · Rx · Rz), then the frame, then W:
//
//   ray_camera = W · B · Ry(yaw) · Rx(pitch) · Rz(roll) · (x, y, 1)
//
// In zenith's frustum frame (x right, y up, −z forward; C = diag(1, −1, −1)
// takes it to S) that is F · R(yaw, pitch, roll) with R the rotation of
// PlanarFrustum (warp/planar_projection.h, the same three turns) and
// F = W · B · C; without a frame F = I (the viewer's axes are the camera's).
// The region's planar projection has the yaw, pitch and roll of F · R.
#include <memory>
#include <optional>
#include <utility>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include "warp/mpcdi.h"
#include "warp/orientation_angles.h"
#include "warp/planar_projection.h"
#include "warp/projection.h"

namespace zenith::warp {

/// What a viewport config adds to an MPCDI region to make its rays.
struct MpcdiViewOptions {
  /// The eye, the origin of the rays of a 3D geometry warp, in the display's
  /// 3D frame and the warp's unit (<geometricUnit>). Unset: the origin of the
  /// 3D data when <originOf3DData> is idealEyePoint, else an error.
  std::optional<glm::dvec3> eye;
  /// The size of the image a 2D warp (3d) or distortion map (sl) addresses:
  /// the frustum's image. Unset: the region's xResolution × yResolution.
  std::optional<std::pair<int, int>> source_size_px;
};

/// Whether the file defines the region's rays (profiles 3d, sl, a3) rather
/// than a projection given with it (2d).
bool mpcdi_region_defines_rays(const MpcdiFile& file);

/// Whether the region's geometry warp holds 3D points of the screen.
bool mpcdi_region_has_3d_warp(const MpcdiRegion& region);

/// F = W · B · C of the header: the coordinate frame's turn in zenith's camera
/// frame. B's columns are the frame's pitch, yaw and roll vectors made exactly
/// orthonormal (roll normalized, yaw made orthogonal to it, pitch = yaw × roll),
/// a change within the loader's 1e-3 tolerance.
glm::dmat3 mpcdi_frame_rotation(const MpcdiCoordinateFrame& frame);

/// The yaw, pitch and roll (PlanarFrustum's conventions, yaw and roll in
/// (−180, 180], pitch in [−90, 90]) of a rotation from a frustum's frame to
/// the camera frame: the inverse of PlanarProjection::rotation(). Pitch from
/// atan2 (well conditioned at ±90°, where yaw and roll share one turn and yaw
/// is taken from the axis as it lies).
YawPitchRollDeg yaw_pitch_roll_of(const glm::dmat3& rotation);

/// The region's frustum in zenith's camera frame: its edge angles, and the
/// yaw, pitch and roll of F · R (its own angles composed with its coordinate
/// frame; F = I without one). The region must have a frustum.
PlanarFrustum mpcdi_planar_frustum(const MpcdiRegion& region);

/// The projection of a width × height px output showing the region of a 3d,
/// sl or a3 file (mpcdi_region_defines_rays):
///  * a 3D geometry warp (a3, sl; 3d when the file says so): per sample the
///    screen point P; the ray W · (P − eye) (options.eye). The rays are
///    charted by an azimuthal equidistant fisheye of 360° (an axis among up,
///    ±45° and ±90° toward forward or backward, the one whose opposite lies
///    farthest from every ray, at least 15°) and interpolated there as the file's
///    <interpolation> asks: a WarpedProjection like those of the 2D formats, exact at
///    the samples;
///  * else the frustum: a PlanarProjection of mpcdi_planar_frustum(); with a
///    2D warp (3d) or a distortion map (sl) a WarpedProjection over it, the
///    frustum's image at options.source_size_px.
/// Throws std::runtime_error naming the archive, the descriptor's line, the
/// region and the element: an a3 region without a 3D warp, a 3D warp without
/// an eye (origin not idealEyePoint, no options.eye), one with no point away
/// from the eye or whose points surround it, a frustum edge the planar
/// projection cannot show (|angle| ≥ 89°).
std::shared_ptr<const Projection> mpcdi_region_projection(const MpcdiFile& file, const MpcdiRegion& region,
                                                          int width_px, int height_px,
                                                          const MpcdiViewOptions& options = {});

/// The viewport config "projection" object (docs/projections.md) of the image
/// a projection from mpcdi_region_projection() maps its pixels into: a
/// PlanarProjection's own, or a WarpedProjection's base (the frustum's planar,
/// or a 3D warp's 360° fisheye chart); null for any other projection. Loaded
/// at that image's size, it gives the same rays (the exported configs of
/// `zenith export-calibration` write it as the output's "projection").
nlohmann::json mpcdi_source_projection_spec(const Projection& projection);

}  // namespace zenith::warp
