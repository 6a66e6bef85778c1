#pragma once
// Smooth interpolation of orientations: spherical quadrangle interpolation
// (squad), Shoemake, "Animating rotation with quaternion curves", SIGGRAPH
// 1985, and his "Quaternion calculus for animation" course notes (1987).
//
// Between keys q_i and q_{i+1}, at fraction h ∈ [0, 1]:
//   squad = slerp(slerp(q_i, q_{i+1}, h), slerp(s_i, s_{i+1}, h), 2h(1 − h))
// with the inner control points
//   s_i = q_i exp(−(log(q_i⁻¹ q_{i+1}) + log(q_i⁻¹ q_{i−1})) / 4),
// which make the angular velocity continuous across keys (a C¹ curve on the
// unit sphere of quaternions). At the first and last key s = q (the curve
// starts and ends like a slerp). Passes through every key exactly.
//
// q and −q are the same rotation; the keys are first made sign-continuous
// (each key negated if it is more than 90° from the previous one in the
// 4D sense, i.e. dot < 0) so every segment takes the shortest arc.
#include <cstddef>
#include <vector>

#include <glm/gtc/quaternion.hpp>

namespace zenith::show {

/// Quaternion log of a unit quaternion (0, θ v) for (cos θ, sin θ v).
glm::dquat quaternion_log(const glm::dquat& unit);
/// Quaternion exp of a pure quaternion (0, θ v): (cos θ, sin θ v).
glm::dquat quaternion_exp(const glm::dquat& pure);
/// Slerp along the arc from a to b as given (no sign flip), t ∈ [0, 1]; exactly a at 0.
glm::dquat slerp_arc(const glm::dquat& a, const glm::dquat& b, double t);

class SquadCurve {
 public:
  /// Unit quaternions, at least one.
  explicit SquadCurve(std::vector<glm::dquat> keys);

  std::size_t segments() const { return keys_.size() < 2 ? 1 : keys_.size() - 1; }
  /// The unit orientation on segment i at fraction h ∈ [0, 1]; the key
  /// itself at 0 and 1 (possibly negated for sign continuity).
  glm::dquat at(std::size_t segment, double fraction) const;
  /// The keys after sign continuity.
  const std::vector<glm::dquat>& keys() const { return keys_; }

 private:
  std::vector<glm::dquat> keys_, control_;
};

}  // namespace zenith::show
