#include "show/camera_track.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "show/key_span.h"

namespace zenith::show {
namespace {

bool all_on_one_surface(const std::vector<CameraKey>& keys) {
  for (const CameraKey& key : keys)
    if (!key.placement.surface || key.placement.reference_body != keys.front().placement.reference_body) return false;
  return true;
}

std::vector<glm::dvec3> path_points(const std::vector<CameraKey>& keys, bool surface) {
  std::vector<glm::dvec3> points;
  for (const CameraKey& key : keys) {
    const auto& s = key.placement.surface;
    points.push_back(surface ? scene::direction_from_latitude_longitude(s->latitude_rad, s->longitude_rad)
                             : key.placement.camera.position_m);
  }
  return points;
}

std::vector<glm::dquat> orientations(const std::vector<CameraKey>& keys) {
  std::vector<glm::dquat> q;
  for (const CameraKey& key : keys) q.push_back(key.placement.camera.orientation);
  return q;
}

std::vector<double> times(const std::vector<CameraKey>& keys) {
  std::vector<double> t;
  for (const CameraKey& key : keys) t.push_back(key.t_s);
  return t;
}

}  // namespace

CameraTrack::CameraTrack(const std::vector<CameraKey>& keys, const std::vector<scene::Body>& bodies)
    : times_s_(times(keys)),
      path_(path_points(keys, !keys.empty() && all_on_one_surface(keys))),
      knot_at_time_(times_s_, path_.knots()),
      orientation_(orientations(keys)) {
  if (all_on_one_surface(keys)) {
    const scene::Body& body = bodies.at(keys.front().placement.reference_body);
    surface_body_ = keys.front().placement.reference_body;
    body_centre_m_ = body.position_m;
    body_orientation_ = body.orientation;
    body_radius_m_ = body.radius_m;
    std::vector<double> log_altitude;
    for (const CameraKey& key : keys) log_altitude.push_back(std::log(key.placement.surface->altitude_m));
    log_altitude_.emplace(times_s_, log_altitude);
  }
}

glm::dvec3 CameraTrack::position_m(double t_s) const {
  const KeySpan span = locate(times_s_, t_s);
  // Where along the segment's knot interval the retimed knot falls (the
  // monotone cubic keeps it inside the interval).
  double fraction = span.fraction;
  if (fraction > 0.0 && fraction < 1.0) {
    const std::vector<double>& knots = path_.knots();
    const double interval = knots[span.segment + 1] - knots[span.segment];
    fraction = interval > 0.0 ? std::clamp((knot_at_time_(t_s) - knots[span.segment]) / interval, 0.0, 1.0) : 0.0;
  }
  const glm::dvec3 point = path_.at(span.segment, fraction);
  if (!surface_body_) return point;
  // p = c + q · (R + h) d, with d the spline of directions back on the unit sphere.
  return body_centre_m_ + body_orientation_ * (glm::normalize(point) * (body_radius_m_ + altitude_m(t_s)));
}

glm::dquat CameraTrack::orientation(double t_s) const {
  const KeySpan span = locate(times_s_, t_s);
  return orientation_.at(span.segment, span.fraction);
}

double CameraTrack::altitude_m(double t_s) const {
  if (!log_altitude_) throw std::logic_error("CameraTrack::altitude_m: the path does not follow a surface");
  return std::exp((*log_altitude_)(t_s));
}

}  // namespace zenith::show
