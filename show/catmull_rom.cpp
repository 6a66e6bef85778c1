#include "show/catmull_rom.h"

#include <cmath>
#include <stdexcept>

#include <glm/geometric.hpp>

namespace zenith::show {

CentripetalCatmullRom::CentripetalCatmullRom(std::vector<glm::dvec3> points) {
  if (points.empty()) throw std::invalid_argument("CentripetalCatmullRom: needs at least one point");
  knots_.push_back(0.0);
  for (std::size_t i = 1; i < points.size(); ++i)
    knots_.push_back(knots_.back() + std::sqrt(glm::length(points[i] - points[i - 1])));
  if (points.size() == 1) {  // a constant: one segment of zero length
    points_.assign(4, points.front());
    return;
  }
  const std::size_t n = points.size();
  points_.reserve(n + 2);
  points_.push_back(2.0 * points[0] - points[1]);
  points_.insert(points_.end(), points.begin(), points.end());
  points_.push_back(2.0 * points[n - 1] - points[n - 2]);
}

glm::dvec3 CentripetalCatmullRom::at(std::size_t segment, double fraction) const {
  if (segment >= segments()) throw std::out_of_range("CentripetalCatmullRom: no such segment");
  const glm::dvec3& p0 = points_[segment];
  const glm::dvec3& p1 = points_[segment + 1];
  const glm::dvec3& p2 = points_[segment + 2];
  const glm::dvec3& p3 = points_[segment + 3];
  if (fraction <= 0.0) return p1;
  if (fraction >= 1.0 || p1 == p2) return fraction >= 1.0 ? p2 : p1;

  // Knot intervals |ΔP|^½. A zero interval (two equal neighbours) carries no
  // weight in its own blend, so any positive stand-in keeps the formulas
  // defined without changing the curve: use the segment's own.
  const double d12 = std::sqrt(glm::length(p2 - p1));
  auto interval = [d12](const glm::dvec3& a, const glm::dvec3& b) {
    const double d = std::sqrt(glm::length(b - a));
    return d > 0.0 ? d : d12;
  };
  const double t0 = 0.0;
  const double t1 = t0 + interval(p0, p1);
  const double t2 = t1 + d12;
  const double t3 = t2 + interval(p2, p3);
  const double t = t1 + fraction * (t2 - t1);

  // Barry–Goldman pyramid: three linear blends, two, then one.
  const glm::dvec3 a1 = ((t1 - t) * p0 + (t - t0) * p1) / (t1 - t0);
  const glm::dvec3 a2 = ((t2 - t) * p1 + (t - t1) * p2) / (t2 - t1);
  const glm::dvec3 a3 = ((t3 - t) * p2 + (t - t2) * p3) / (t3 - t2);
  const glm::dvec3 b1 = ((t2 - t) * a1 + (t - t0) * a2) / (t2 - t0);
  const glm::dvec3 b2 = ((t3 - t) * a2 + (t - t1) * a3) / (t3 - t1);
  return ((t2 - t) * b1 + (t - t1) * b2) / (t2 - t1);
}

}  // namespace zenith::show
