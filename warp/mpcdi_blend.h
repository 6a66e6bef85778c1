#pragma once
// An MPCDI region's alpha and beta maps (VESA MPCDI v2.0 §2.4, §3.7) on the
// pixels of the output that shows the region: the per-pixel α and β of the
// output stage, P' = α · P · (1 − β) + β (warp/blending.h), when the output's
// "blend" is {"type": "mpcdi"} (docs/warp-meshes.md, "Alpha and beta maps").
//
// Placement. §3.7 says a blend map's "lookup and storage is the same as
// OpenGL UV mapping": the map is a texture stretched over the projector's
// raster, (0, 0) its top-left corner and (1, 1) its bottom-right one, whatever
// the map's size (§3.7: "Either file can be different in image size"). Output
// pixel (x, y) of a W × H output reads the map at its centre,
//     u = (x + ½) / W,   v = (y + ½) / H,
// and a w × h map's sample (i, j) sits at its own texel centre ((i + ½) / w,
// (j + ½) / h): with s = u · w − ½ and t = v · h − ½, clamped to [0, w − 1] and
// [0, h − 1] (OpenGL's clamp-to-edge), the value is the bilinear
//     m(s, t) = (1 − fs)(1 − ft) m(i, j) + fs (1 − ft) m(i + 1, j)
//             + (1 − fs) ft m(i, j + 1) + fs ft m(i + 1, j + 1),   i = ⌊s⌋, fs = s − i.
// A map of the output's own size is read sample for sample.
//
// Gamma. An alpha map stores α^(1/γ) (§2.3: Pg = Pl^γ read as the stored value
// Pg's linear weight; gammaEmbedded γ): each sample is decoded to linear light
// first, value^γ, then interpolated, so the interpolant is a weight in linear
// light between its neighbours' (two projectors' maps that sum to 1 at their
// samples still sum to 1 between them where their samples coincide). Beta maps
// carry no gamma (§3.6.1 gives gammaEmbedded to alphaMap only): linear.
//
// Channels. Colour levels 4 and 5 (table 3-3) allow RGB maps, one α and β per
// channel. zenith's output stage takes one α and one β a pixel: an RGB map
// whose three channels are equal (grey written as RGB) is read as grey; one
// whose channels differ is refused (check_grey_blend_map()).
#include <string>
#include <vector>

#include "warp/mpcdi.h"

namespace zenith::warp {

/// The map's linear values (value^gamma_embedded, channel 0) at the pixel
/// centres of a width_px × height_px output, row 0 at the top, x fastest, as
/// the header says. Throws std::invalid_argument for a size below 1 or an empty map.
std::vector<float> sample_mpcdi_blend_map(const MpcdiBlendMap& map, int width_px, int height_px);

/// Throws std::runtime_error "<archive>:<descriptor>:<line>: region '<id>':
/// <what> '<member>' ..." naming the first pixel whose channels differ, for an
/// RGB map (per-channel α or β, colour levels 4 and 5) that is not grey.
/// `source` is "<archive>:<descriptor>" as the loader's messages start.
void check_grey_blend_map(const MpcdiBlendMap& map, const std::string& source, const std::string& region_id,
                          const char* what);

}  // namespace zenith::warp
