#pragma once
// Centripetal Catmull–Rom splines (3D, double).
//
// Each segment P_i → P_{i+1} is the cubic through four neighbours P_{i−1} ..
// P_{i+2}, evaluated with Barry & Goldman's pyramidal formulation ("A
// recursive evaluation algorithm for a class of Catmull-Rom splines",
// SIGGRAPH 1988) over knots spaced by the square root of the chord lengths,
// t_{j+1} = t_j + |P_{j+1} − P_j|^½. Yuksel, Schaefer & Keyser ("On the
// parameterization of Catmull-Rom curves", 2009) show that this centripetal
// choice, unlike the uniform one, never forms cusps or self-intersections
// within a segment and follows the control polygon tightly, which is what a
// camera path through unevenly spaced keys needs.
//
// Ends: the missing outer neighbours are reflections, P_{−1} = 2 P_0 − P_1 and
// P_{n+1} = 2 P_n − P_{n−1}, so the path leaves the first key heading toward
// the second (a duplicated end key would make a zero-length knot interval).
// With collinear, evenly spaced keys every knot interval is equal and the
// spline reproduces the straight line at constant speed exactly.
#include <cstddef>
#include <vector>

#include <glm/vec3.hpp>

namespace zenith::show {

class CentripetalCatmullRom {
 public:
  /// At least one point.
  explicit CentripetalCatmullRom(std::vector<glm::dvec3> points);

  std::size_t segments() const { return points_.size() - 3; }
  /// The centripetal knot of each key: 0 at the first, then + |P_{i+1} − P_i|^½ (one per key).
  const std::vector<double>& knots() const { return knots_; }
  /// The point on segment i (from key i to key i + 1) at `fraction` ∈ [0, 1]
  /// of its knot interval; exactly the keys at 0 and 1. A single key is a
  /// constant.
  glm::dvec3 at(std::size_t segment, double fraction) const;

 private:
  std::vector<glm::dvec3> points_;  ///< the keys with a reflected neighbour at each end
  std::vector<double> knots_;
};

}  // namespace zenith::show
