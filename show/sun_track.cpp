#include "show/sun_track.h"

#include <cmath>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "show/key_span.h"

namespace zenith::show {
namespace {

std::vector<double> times(const std::vector<SunKey>& keys) {
  std::vector<double> t;
  for (const SunKey& key : keys) t.push_back(key.t_s);
  return t;
}

std::vector<double> travelled(const std::vector<SunKey>& keys) {
  std::vector<double> angle{0.0};
  for (std::size_t i = 1; i < keys.size(); ++i)
    angle.push_back(angle.back() + angle_between_rad(keys[i - 1].sun.direction, keys[i].sun.direction));
  return angle;
}

std::vector<double> angular_radii(const std::vector<SunKey>& keys) {
  std::vector<double> r;
  for (const SunKey& key : keys) r.push_back(key.sun.angular_radius_rad);
  return r;
}

}  // namespace

double angle_between_rad(const glm::dvec3& a, const glm::dvec3& b) {
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

SunTrack::SunTrack(const std::vector<SunKey>& keys)
    : times_s_(times(keys)),
      travelled_at_key_rad_(travelled(keys)),
      travelled_rad_(times_s_, travelled_at_key_rad_),
      angular_radius_rad_(times_s_, angular_radii(keys)) {
  for (const SunKey& key : keys) {
    directions_.push_back(glm::normalize(key.sun.direction));
    if (key.sun.irradiance_W_m2_nm.size() != keys.front().sun.irradiance_W_m2_nm.size())
      throw std::invalid_argument("SunTrack: every key needs the same number of irradiance values");
  }
  for (std::size_t w = 0; w < keys.front().sun.irradiance_W_m2_nm.size(); ++w) {
    std::vector<double> values;
    for (const SunKey& key : keys) values.push_back(key.sun.irradiance_W_m2_nm[w]);
    irradiance_W_m2_nm_.emplace_back(times_s_, values);
  }
}

scene::Sun SunTrack::at(double t_s) const {
  scene::Sun sun;
  const KeySpan span = locate(times_s_, t_s);
  const std::size_t i = span.segment;
  if (directions_.size() == 1 || span.fraction == 0.0) {
    sun.direction = directions_[i];
  } else if (span.fraction == 1.0) {
    sun.direction = directions_[i + 1];
  } else {
    const double arc = travelled_at_key_rad_[i + 1] - travelled_at_key_rad_[i];
    const double along = arc > 0.0 ? (travelled_rad_(t_s) - travelled_at_key_rad_[i]) / arc : 0.0;
    // slerp(a, b, f) = [sin((1 − f) θ) a + sin(f θ) b] / sin θ, θ the arc.
    const glm::dvec3& a = directions_[i];
    const glm::dvec3& b = directions_[i + 1];
    sun.direction =
        arc > 1e-12 ? glm::normalize((std::sin((1.0 - along) * arc) * a + std::sin(along * arc) * b) / std::sin(arc))
                    : a;
  }
  sun.angular_radius_rad = angular_radius_rad_(t_s);
  for (const MonotoneCubic& irradiance : irradiance_W_m2_nm_) sun.irradiance_W_m2_nm.push_back(irradiance(t_s));
  return sun;
}

}  // namespace zenith::show
