#include "atmosphere/reference/shell_traversal.h"

#include <algorithm>
#include <cmath>

namespace zenith::atmosphere::reference {

ShellTraversal::ShellTraversal(const MajorantGrid& grid, const Ray& ray, double t_begin_m)
    : grid_(&grid),
      ray_(&ray),
      t_m_(t_begin_m),
      shell_(grid.shell_of_radius(ray.radius_at(t_begin_m))),
      inward_(t_begin_m < ray.perigee_t_m()) {}

bool ShellTraversal::next(ShellSegment& segment) {
  if (done_) return false;
  const double p = ray_->impact_parameter_m();
  const double t_c = ray_->perigee_t_m();
  auto half_chord = [p](double radius) { return std::sqrt(std::max(0.0, (radius - p) * (radius + p))); };

  segment.begin_t_m = t_m_;
  segment.shell = shell_;
  const double lower = grid_->boundary_radius_m(shell_);
  if (inward_ && p < lower) {
    // Leaves this shell through its lower boundary, into the shell below or the ground.
    segment.end_t_m = std::max(t_m_, t_c - half_chord(lower));
    if (shell_ == 0) {
      done_ = hit_ground_ = true;
      ground_t_m_ = segment.end_t_m;
    } else {
      --shell_;
    }
  } else {
    // Outward leg (or the perigee is in this shell): leaves through the upper boundary.
    inward_ = false;
    const double upper = grid_->boundary_radius_m(shell_ + 1);
    segment.end_t_m = std::max(t_m_, t_c + half_chord(upper));
    if (shell_ + 1 == grid_->shell_count()) {
      done_ = true;
    } else {
      ++shell_;
    }
  }
  t_m_ = segment.end_t_m;
  return true;
}

}  // namespace zenith::atmosphere::reference
