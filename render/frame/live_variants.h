#pragma once
// Which program variant (FrameVariant) a live frame — a window's, a cluster
// node's — draws with, so that no frame waits for a compile when the scene
// changes what its programs may leave out (RenderOptions::background_variant_builds).
//
// A variant compiles code out: the eclipse code where no body's shadow can
// fall, the albedo's level of detail where every footprint is under a texel.
// A variant's programs not yet built cost their builds on the frame that
// first needs them: on llvmpipe 0.5–1.2 s with Mesa's cache cold, tens of
// milliseconds with it warm — a dome's every projector held that long when
// the three worlds' shadows parted mid-show. Yet the variant in use serves
// any frame that needs less than it has, with the same pixels: the frame
// draws with it while the leaner variant's programs build (and their first
// dispatches warm) on a second thread, and the first frame after that draws
// with the leaner one. While nothing else builds, the general variant of the
// projection (the eclipse code where the scene has bodies to cast shadows,
// the albedo at every level) is built ahead as well, so that a later frame
// needing more than the lean variant has finds it ready. Only a frame that
// needs a variant no built one serves (the first frame, a new projection
// kind) builds it itself.
//
// Whether a variant is built depends on the frame: its programs are per tile
// kind, and a frame may have tiles another had not. `Built` answers for the
// frame at hand (every program it would draw with, built and warmed).
#include <functional>
#include <optional>

#include "render/frame/gpu_atmosphere.h"

namespace zenith::render {

/// Whether `general`'s programs draw every frame `specific`'s draw, with the
/// same pixels: the same projection kind, the eclipse code where `specific`
/// has it (without a shadow to draw it multiplies by one), the albedo at every
/// level where `specific` reads level 0 only (its level is 0 there).
bool variant_serves(const FrameVariant& general, const FrameVariant& specific);

class LiveVariants {
 public:
  /// Whether the frame at hand could draw with a variant without building a program.
  using Built = std::function<bool(const FrameVariant&)>;

  /// The variant whose programs the frame starts before its tiles are known:
  /// the one in use (`wanted` on the first frame).
  FrameVariant provisional(const FrameVariant& wanted) const { return in_use_.value_or(wanted); }
  /// What the frame that wants `wanted` draws with: `wanted` where built;
  /// else the variant in use where it serves `wanted`; else `wanted` (the
  /// frame builds it).
  FrameVariant choose(const FrameVariant& wanted, const Built& built) const;
  /// A frame drew with `used` wanting `wanted`; `shadows_can_fall`: the
  /// scene's bodies could eclipse one another somewhere (eclipses on, two
  /// bodies or more). Returns the variant to build for later frames where
  /// one is missing and none is building: `wanted`, else the general one.
  std::optional<FrameVariant> drew(const FrameVariant& used, const FrameVariant& wanted, bool shadows_can_fall,
                                   const Built& built);
  /// The variant drew() returned is built, its first dispatches warmed.
  void built_ahead() { building_.reset(); }
  /// The variant building for later frames, if any.
  const std::optional<FrameVariant>& building() const { return building_; }

 private:
  std::optional<FrameVariant> in_use_, building_;
};

}  // namespace zenith::render
