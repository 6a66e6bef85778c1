#include "render/frame/live_variants.h"

namespace zenith::render {

bool variant_serves(const FrameVariant& general, const FrameVariant& specific) {
  const bool general_air = general.eclipses && general.air_shadows,
             specific_air = specific.eclipses && specific.air_shadows;
  return general.projection_kind == specific.projection_kind && (general.eclipses || !specific.eclipses) &&
         (general_air || !specific_air) && (specific.albedo_lod0 || !general.albedo_lod0);
}

FrameVariant LiveVariants::choose(const FrameVariant& wanted, const Built& built) const {
  // Most frames want the variant in use: no need to ask about its programs.
  if ((in_use_ && in_use_->key() == wanted.key()) || built(wanted)) return wanted;
  if (in_use_ && variant_serves(*in_use_, wanted)) return *in_use_;
  return wanted;
}

std::optional<FrameVariant> LiveVariants::drew(const FrameVariant& used, const FrameVariant& wanted,
                                               bool shadows_can_fall, const Built& built) {
  in_use_ = used;
  if (building_) return std::nullopt;
  FrameVariant general = used;
  general.eclipses = shadows_can_fall;
  general.air_shadows = shadows_can_fall;
  general.albedo_lod0 = false;
  for (const FrameVariant& next : {wanted, general})
    if (next.key() != used.key() && !built(next)) return building_ = next;
  return std::nullopt;
}

}  // namespace zenith::render
