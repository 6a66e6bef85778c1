#pragma once
// Plausibility checks of a warp map's values. A map read with the wrong
// conventions (warp/warp_map_conventions.h) loads without error but shows the
// wrong picture; these checks find the common cases and say what to set. They
// warn, never refuse: a strange map may still be what its author meant.
//
//  * Collapsed: every valid sample maps to one point of the source image (the
//    spread of u and of v both at most 1e-6). An all-zero map read as absolute
//    values is the Evans & Sutherland offset map meaning "no distortion".
//  * Looks like offsets: read as absolute values, every stored u and v lies in
//    [−0.25, 0.25]: a projector showing only a corner of its source image that
//    small is implausible, offsets from the regular grid are not.
//  * Mostly outside: more than half of the valid samples map outside the
//    source image ([0, 1] in u or v, 1e-3 tolerance): the v direction, the row
//    order or the values convention is likely wrong.
#include <string>
#include <vector>

#include "warp/pfm.h"
#include "warp/warp_map_conventions.h"

namespace zenith::warp {

/// Largest |u|, |v| of an absolute map that is taken for offsets.
inline constexpr double kOffsetLikeMaxValue = 0.25;
/// Largest spread of u and of v of a map that is taken as collapsed to one point.
inline constexpr double kCollapsedSpread = 1e-6;
/// Tolerance of the [0, 1] range of the source image.
inline constexpr double kSourceRangeTolerance = 1e-3;

/// The warnings for a 3-channel warp map (channels 0, 1 = stored u, v; a sample
/// with a non-finite u or v has no data) read with `conventions`; each starts
/// with `source` and names what to set. Empty when the map looks plausible or
/// has no valid sample.
std::vector<std::string> warp_map_warnings(const PfmImage& map, const WarpMapConventions& conventions,
                                           const std::string& source);

}  // namespace zenith::warp
