#include "render/frame/frame_sky.h"

#include <stdexcept>

namespace zenith::render {

const astro::SkyPositions& FrameSky::positions() const {
  if (clock_ == nullptr) throw std::logic_error("FrameSky: the scene has no sky clock");
  if (!positions_) positions_.emplace(astro::AstroTime::from_utc(clock_->time), clock_->site);
  return *positions_;
}

}  // namespace zenith::render
