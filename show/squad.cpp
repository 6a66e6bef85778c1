#include "show/squad.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace zenith::show {
namespace {

double vector_length(const glm::dquat& q) { return std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z); }

}  // namespace

glm::dquat quaternion_log(const glm::dquat& q) {
  const double s = vector_length(q);
  if (s < 1e-300) return {0.0, 0.0, 0.0, 0.0};
  const double theta = std::atan2(s, q.w);  // accurate for every angle, unlike acos(w)
  const double k = theta / s;
  return {0.0, k * q.x, k * q.y, k * q.z};
}

glm::dquat quaternion_exp(const glm::dquat& p) {
  const double theta = vector_length(p);
  if (theta < 1e-300) return {1.0, 0.0, 0.0, 0.0};
  const double k = std::sin(theta) / theta;
  return {std::cos(theta), k * p.x, k * p.y, k * p.z};
}

glm::dquat slerp_arc(const glm::dquat& a, const glm::dquat& b, double t) {
  if (t == 0.0) return a;
  if (t == 1.0) return b;
  const double cos_angle = glm::dot(a, b);
  // Nearly the same rotation: the linear blend is exact to rounding.
  if (std::abs(cos_angle) > 1.0 - 1e-12) return glm::normalize(a * (1.0 - t) + b * t);
  const double angle = std::acos(std::clamp(cos_angle, -1.0, 1.0));
  const double sin_angle = std::sin(angle);
  return a * (std::sin((1.0 - t) * angle) / sin_angle) + b * (std::sin(t * angle) / sin_angle);
}

SquadCurve::SquadCurve(std::vector<glm::dquat> keys) : keys_(std::move(keys)) {
  if (keys_.empty()) throw std::invalid_argument("SquadCurve: needs at least one key");
  for (glm::dquat& q : keys_) q = glm::normalize(q);
  for (std::size_t i = 1; i < keys_.size(); ++i)
    if (glm::dot(keys_[i - 1], keys_[i]) < 0.0) keys_[i] = -keys_[i];
  const std::size_t n = keys_.size();
  control_ = keys_;
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const glm::dquat inverse = glm::conjugate(keys_[i]);
    const glm::dquat to_next = quaternion_log(inverse * keys_[i + 1]);
    const glm::dquat to_previous = quaternion_log(inverse * keys_[i - 1]);
    control_[i] = glm::normalize(keys_[i] * quaternion_exp((to_next + to_previous) * -0.25));
  }
}

glm::dquat SquadCurve::at(std::size_t segment, double h) const {
  if (keys_.size() == 1) return keys_[0];
  if (segment >= segments()) throw std::out_of_range("SquadCurve: no such segment");
  if (h <= 0.0) return keys_[segment];
  if (h >= 1.0) return keys_[segment + 1];
  const glm::dquat outer = slerp_arc(keys_[segment], keys_[segment + 1], h);
  const glm::dquat inner = slerp_arc(control_[segment], control_[segment + 1], h);
  return glm::normalize(slerp_arc(outer, inner, 2.0 * h * (1.0 - h)));
}

}  // namespace zenith::show
