#pragma once
// Walks a ray through the concentric shells of a MajorantGrid, segment by
// segment, ending where it leaves the top of the atmosphere or hits the ground.
//
// Along a straight ray r(t) = √(p² + (t − t_c)²) first decreases (t < t_c, the
// inward leg) then increases, so the shells are visited in a known order: inward
// through the lower boundaries ρ_k (crossed at t_c − √(ρ_k² − p²)) until the
// perigee lies inside a shell (ρ_k ≤ p), then outward through the upper ones
// (t_c + √(ρ_{k+1}² − p²)). Crossings are computed from (p, t_c) only, so the
// walk cannot get stuck on a boundary by rounding; the ground is hit when the
// inward leg crosses ρ_0 = R_ground.
#include <cstddef>

#include "atmosphere/reference/geometry.h"
#include "atmosphere/reference/majorant_grid.h"

namespace zenith::atmosphere::reference {

struct ShellSegment {
  double begin_t_m = 0.0, end_t_m = 0.0;  ///< the segment of the ray, begin ≤ end
  std::size_t shell = 0;                  ///< the grid shell it lies in
};

class ShellTraversal {
 public:
  /// Starts at parameter t_begin, which must be inside the atmosphere shell up to
  /// rounding (e.g. the begin of atmosphere_interval, or a scattering point).
  ShellTraversal(const MajorantGrid& grid, const Ray& ray, double t_begin_m);

  /// The next segment, or false when the ray has left the top or hit the ground.
  bool next(ShellSegment& segment);
  /// After next() returned false: whether the walk ended on the ground, and where.
  bool hit_ground() const { return hit_ground_; }
  double ground_t_m() const { return ground_t_m_; }

 private:
  const MajorantGrid* grid_;
  const Ray* ray_;
  double t_m_;
  std::size_t shell_;
  bool inward_;
  bool done_ = false, hit_ground_ = false;
  double ground_t_m_ = 0.0;
};

}  // namespace zenith::atmosphere::reference
