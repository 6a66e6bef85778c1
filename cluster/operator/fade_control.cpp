#include "cluster/operator/fade_control.h"

#include <cmath>
#include <stdexcept>

#include "core/strings.h"

namespace zenith::cluster {

using core::cat;

double fade_curve(double u) {
  if (!(u > 0.0)) return 0.0;
  if (u >= 1.0) return 1.0;
  return u * u * (3.0 - 2.0 * u);
}

FadeControl::FadeControl(double fps) : fps_(fps) {
  if (!(std::isfinite(fps) && fps > 0.0)) throw std::invalid_argument(cat("fade: frame rate ", fps, " Hz must be > 0"));
}

void FadeControl::start(std::uint64_t frame, double level, std::optional<glm::dvec3> colour, double seconds) {
  if (!(level >= 0.0 && level <= scene::kMaxFadeLevel))
    throw std::invalid_argument(cat("fade: level = ", level, ": must be in [0, 1]"));
  if (!(seconds >= 0.0 && seconds <= kMaxFadeSeconds))
    throw std::invalid_argument(cat("fade: seconds = ", seconds, ": must be in [0, ", kMaxFadeSeconds, "] s"));
  if (colour)
    for (int i = 0; i < 3; ++i)
      if (!((*colour)[i] >= 0.0 && (*colour)[i] <= 1.0))
        throw std::invalid_argument(cat("fade: colour component ", i, " = ", (*colour)[i], ": must be in [0, 1]"));
  from_ = at(frame);
  // From the picture the colour is not visible yet: the new one at once, so a
  // fade to red does not pass through the last fade's colour.
  if (colour && from_.level == 0.0) from_.colour = *colour;
  to_ = {level, colour ? *colour : from_.colour};
  start_ = frame;
  frames_ = static_cast<std::uint64_t>(std::llround(seconds * fps_));
}

scene::FadeState FadeControl::at(std::uint64_t frame) const {
  if (frame < start_) return from_;
  const double u = frames_ == 0 ? 1.0 : static_cast<double>(frame - start_ + 1) / static_cast<double>(frames_);
  const double s = fade_curve(u);
  if (s >= 1.0) return to_;
  return {from_.level + (to_.level - from_.level) * s, from_.colour + (to_.colour - from_.colour) * s};
}

bool FadeControl::active(std::uint64_t frame) const { return frames_left(frame) > 0 || at(frame).level > 0.0; }

void FadeControl::apply(scene::FadeState& fade, std::uint64_t frame) const {
  if (active(frame)) fade = at(frame);
}

std::uint64_t FadeControl::frames_left(std::uint64_t frame) const {
  const std::uint64_t end = start_ + frames_;  // the first frame at the target is end − 1 (n ≥ 1) or start (n = 0)
  if (frames_ == 0 || frame + 1 >= end) return 0;
  return end - 1 - frame;
}

}  // namespace zenith::cluster
