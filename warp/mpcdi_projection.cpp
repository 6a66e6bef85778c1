#include "warp/mpcdi_projection.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "core/units.h"
#include "warp/fisheye_projection.h"
#include "warp/warp_mesh.h"
#include "warp/warped_projection.h"

namespace zenith::warp {
namespace {

using core::kDeg;
using core::kRadToDeg;

/// W: the display's 3D frame (X left, Y up, Z forward, the standard's
/// preference) → zenith's camera frame (x right, y up, −z forward).
const glm::dmat3 kWorldToCamera(-1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, -1.0);
/// C: zenith's frustum frame (y up, −z forward) ↔ the standard's viewer frame S
/// (Y down, Z forward); its own inverse.
const glm::dmat3 kZenithToViewer(1.0, 0.0, 0.0, 0.0, -1.0, 0.0, 0.0, 0.0, -1.0);

/// The side of the square chart of a 3D warp's rays, px: it sets only the
/// scale of its (u, v) (the rays do not depend on it).
constexpr int kChartPx = 4096;
/// The tilts the chart's axis is chosen from (degrees; fisheye tilt: from up
/// toward forward), and the least angle, degrees, between any ray and the
/// axis's opposite, where the chart stretches without bound.
constexpr std::array<double, 5> kChartTilts = {0.0, 45.0, 90.0, -45.0, -90.0};
constexpr double kMinAntipodeDeg = 15.0;

/// "show.mpcdi:mpcdi.xml:12: region 'p1': " for messages.
std::string where(const MpcdiFile& file, const MpcdiRegion& region, int line) {
  std::string text = file.path;
  text += ':';
  text += file.descriptor;
  if (line > 0) text += ':' + std::to_string(line);
  text += ": region '";
  text += region.id;
  text += "': ";
  return text;
}

/// The eye of a 3D warp: given, or the origin of the data when it is the ideal eye point.
glm::dvec3 warp_eye(const MpcdiFile& file, const MpcdiRegion& region, const MpcdiGeometryWarp& warp,
                    const MpcdiViewOptions& options) {
  if (options.eye) return *options.eye;
  if (warp.origin_of_3d_data == "idealEyePoint") return glm::dvec3(0.0);
  throw std::runtime_error(where(file, region, warp.line) + "<geometryWarpFile> '" + warp.path +
                           "' holds 3D points of the screen with <originOf3DData> " + warp.origin_of_3d_data +
                           ", not idealEyePoint: give the eye, the origin of the rays, in the viewport's \"warp\": "
                           "{\"eye\": [x, y, z]} (the display's frame, in " +
                           warp.geometric_unit + "; docs/warp-meshes.md)");
}

/// A 3D geometry warp as a WarpedProjection over a 360° fisheye chart.
std::shared_ptr<const Projection> point_warp_projection(const MpcdiFile& file, const MpcdiRegion& region, int width_px,
                                                        int height_px, const MpcdiViewOptions& options) {
  const MpcdiGeometryWarp& warp = *region.geometry_warp;
  const glm::dvec3 eye = warp_eye(file, region, warp, options);
  const PfmImage& map = warp.map;
  // The camera-frame direction of every sample from the eye; none where the
  // sample is NaN or at the eye.
  std::vector<std::optional<glm::dvec3>> directions(static_cast<std::size_t>(map.width) * map.height);
  bool any = false;
  for (int j = 0; j < map.height; ++j)
    for (int i = 0; i < map.width; ++i) {
      const glm::dvec3 p(map.at(i, j, 0), map.at(i, j, 1), map.at(i, j, 2));
      const glm::dvec3 d = kWorldToCamera * (p - eye);
      if (!std::isfinite(d.x) || !std::isfinite(d.y) || !std::isfinite(d.z) || glm::length(d) == 0.0) continue;
      directions[static_cast<std::size_t>(j) * map.width + i] = glm::normalize(d);
      any = true;
    }
  const std::string element = "<geometryWarpFile> '" + warp.path + "': ";
  if (!any) throw std::runtime_error(where(file, region, warp.line) + element + "no sample lies away from the eye");

  // The chart's axis: the candidate whose opposite lies farthest from every ray.
  double best_tilt = 0.0, best_clearance = -1.0;
  for (const double tilt : kChartTilts) {
    const glm::dvec3 opposite = -FisheyeProjection(1, 1, {.fov_deg = 360.0, .tilt_deg = tilt}).optical_frame()[2];
    double clearance = 1.0e9;  // the least angle of a ray from the opposite
    for (const auto& d : directions)
      if (d) clearance = std::min(clearance, std::acos(std::clamp(glm::dot(*d, opposite), -1.0, 1.0)));
    if (clearance > best_clearance) best_clearance = clearance, best_tilt = tilt;
  }
  if (best_clearance < kMinAntipodeDeg * kDeg)
    throw std::runtime_error(where(file, region, warp.line) + element + "its screen points surround the eye (rays in " +
                             "nearly every direction: within " + std::to_string(best_clearance * kRadToDeg) +
                             " degrees of down, forward and backward): one projector cannot be charted");
  const auto chart = std::make_shared<FisheyeProjection>(kChartPx, kChartPx,
                                                         FisheyeParameters{.fov_deg = 360.0, .tilt_deg = best_tilt});
  std::vector<WarpNode> nodes(directions.size());
  for (std::size_t k = 0; k < directions.size(); ++k) {
    if (!directions[k]) continue;
    const auto px = chart->pixel(*directions[k]);
    if (!px) continue;  // cannot happen for fov 360 and a unit vector; no data then
    nodes[k] = WarpNode{px->x / kChartPx, px->y / kChartPx, 1.0, true};
  }
  WarpMesh mesh(map.width, map.height, std::move(nodes), file.path + ":" + warp.path, warp.mesh_interpolation);
  return std::make_shared<WarpedProjection>(width_px, height_px, std::move(mesh), chart);
}

}  // namespace

bool mpcdi_region_defines_rays(const MpcdiFile& file) { return file.profile != MpcdiProfile::media_2d; }

bool mpcdi_region_has_3d_warp(const MpcdiRegion& region) {
  return region.geometry_warp && region.geometry_warp->points_3d;
}

glm::dmat3 mpcdi_frame_rotation(const MpcdiCoordinateFrame& frame) {
  // The viewer frame S in the world: X right = pitch, Y down = yaw, Z forward =
  // roll, right-handed (X = Y × Z), made exactly orthonormal.
  const glm::dvec3 forward = glm::normalize(frame.roll_axis);
  const glm::dvec3 down = glm::normalize(frame.yaw_axis - glm::dot(frame.yaw_axis, forward) * forward);
  const glm::dvec3 right = glm::cross(down, forward);
  const glm::dmat3 viewer_to_world(right, down, forward);  // B, columns
  return kWorldToCamera * viewer_to_world * kZenithToViewer;
}

YawPitchRollDeg yaw_pitch_roll_of(const glm::dmat3& rotation) {
  // The frustum's axis is −column 2: (sin ψ cos θ, sin θ, −cos ψ cos θ)
  // (warp/planar_projection.h).
  const glm::dvec3 axis = -rotation[2];
  const double pitch = std::atan2(axis.y, std::hypot(axis.x, axis.z));
  const double yaw = std::atan2(axis.x, -axis.z);
  // With roll 0 the frustum's right and up are R_yaw · R_pitch · x̂ and · ŷ;
  // roll φ turns up to sin φ · right₀ + cos φ · up₀ (column 1).
  const glm::dvec3 right0(std::cos(yaw), 0.0, std::sin(yaw));
  const glm::dvec3 up0(-std::sin(yaw) * std::sin(pitch), std::cos(pitch), std::cos(yaw) * std::sin(pitch));
  const double roll = std::atan2(glm::dot(rotation[1], right0), glm::dot(rotation[1], up0));
  return normalized_yaw_pitch_roll({yaw * kRadToDeg, pitch * kRadToDeg, roll * kRadToDeg});
}

PlanarFrustum mpcdi_planar_frustum(const MpcdiRegion& region) {
  const MpcdiFrustum& f = region.frustum.value();
  PlanarFrustum planar = f.planar();
  if (!region.coordinate_frame) return planar;  // F = I
  const glm::dmat3 own =
      PlanarProjection(1, 1, PlanarFrustum{-1.0, 1.0, -1.0, 1.0, f.yaw_deg, f.pitch_deg, f.roll_deg}).rotation();
  const YawPitchRollDeg total = yaw_pitch_roll_of(mpcdi_frame_rotation(*region.coordinate_frame) * own);
  planar.yaw_deg = total.yaw_deg;
  planar.pitch_deg = total.pitch_deg;
  planar.roll_deg = total.roll_deg;
  return planar;
}

std::shared_ptr<const Projection> mpcdi_region_projection(const MpcdiFile& file, const MpcdiRegion& region,
                                                          int width_px, int height_px,
                                                          const MpcdiViewOptions& options) {
  if (mpcdi_region_has_3d_warp(region)) return point_warp_projection(file, region, width_px, height_px, options);
  if (!region.frustum)
    throw std::runtime_error(where(file, region, region.line) + "profile " + to_string(file.profile) +
                             ": the region has no 3D geometry warp (<geometryWarpFile> of screen points) and no "
                             "<frustum>: nothing gives its rays");
  const WarpMesh* mesh = region.warp_mesh         ? &*region.warp_mesh
                         : region.distortion_mesh ? &*region.distortion_mesh
                                                  : nullptr;
  try {
    const PlanarFrustum frustum = mpcdi_planar_frustum(region);
    if (!mesh) return std::make_shared<PlanarProjection>(width_px, height_px, frustum);
    const auto [source_w, source_h] =
        options.source_size_px.value_or(std::pair{region.x_resolution_px, region.y_resolution_px});
    return std::make_shared<WarpedProjection>(width_px, height_px, *mesh,
                                              std::make_shared<PlanarProjection>(source_w, source_h, frustum));
  } catch (const std::invalid_argument& e) {  // an edge the planar projection cannot show
    throw std::runtime_error(where(file, region, region.frustum->line) + "<frustum>: " + e.what());
  }
}

nlohmann::json mpcdi_source_projection_spec(const Projection& projection) {
  const Projection* image = &projection;
  if (const auto* warped = dynamic_cast<const WarpedProjection*>(image)) image = &warped->base();
  if (const auto* planar = dynamic_cast<const PlanarProjection*>(image)) {
    const PlanarFrustum& f = planar->frustum();
    return {{"type", "planar"},   {"left_deg", f.left_deg}, {"right_deg", f.right_deg}, {"down_deg", f.down_deg},
            {"up_deg", f.up_deg}, {"yaw_deg", f.yaw_deg},   {"pitch_deg", f.pitch_deg}, {"roll_deg", f.roll_deg}};
  }
  if (const auto* fisheye = dynamic_cast<const FisheyeProjection*>(image))
    return {{"type", "fisheye"}, {"fov_deg", fisheye->fov_deg()}, {"tilt_deg", fisheye->tilt_deg()}};
  return nullptr;
}

}  // namespace zenith::warp
