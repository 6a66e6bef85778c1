#pragma once
// Edge blending of overlapping outputs (projectors on a dome) and the black
// level. docs/viewports.md has the equations and the conventions; in short:
//
//  * Every weight here is in LINEAR LIGHT: α = 0.5 means half the light.
//  * Automatic blending: output j's raw weight at a dome direction d is
//        f_j(d) = S(D_j(p_j(d)) / r_j),    S(t) = 3t² − 2t³ on [0, 1] (smoothstep)
//    with p_j(d) = projection_j.pixel(d), D_j(p) the distance in pixels from p
//    to the border of output j's coverage (the image rectangle, and for
//    fisheyes and warp meshes the border of the pixels that have a ray), r_j
//    the ramp width (BlendSource::width_fraction · min(width_j, height_j)), and
//    f_j = 0 where output j does not see d. The blend weight is
//        w_i(d) = f_i(d) / Σ_j f_j(d)
//    over the outputs with automatic blending, so the weights of every
//    direction that some output covers sum to 1 exactly.
//  * Output stage (VESA MPCDI v2.0 §2.4): with P the display-linear value (a
//    fraction of the projector's full white, after tone mapping)
//    P' = P · α · (1 − β) + β, then the display encoding (sRGB). α per pixel
//    from the blend (none, auto, a mask file, an MPCDI region's alpha map);
//    β the output's black_level, or per pixel an MPCDI region's beta map
//    (blend "mpcdi", warp/mpcdi_blend.h).
#include <cstddef>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "warp/viewport_config.h"

namespace zenith::warp {

/// A per-pixel weight α in linear light, row 0 at the top, x fastest; and
/// where the output has a black-level map (an MPCDI region's beta map), β per
/// pixel the same way.
struct BlendMask {
  int width = 0, height = 0;
  std::vector<float> alpha;
  /// β per pixel (width · height values) or empty: β is then the output's one
  /// number (OutputConfig::black_level), which the functions taking a mask
  /// receive beside it.
  std::vector<float> beta{};

  float at(int x, int y) const { return alpha[static_cast<std::size_t>(y) * width + x]; }
  /// β at a pixel: the map's, or `black_level` without one.
  double black_level_at(int x, int y, double black_level) const {
    return beta.empty() ? black_level : beta[static_cast<std::size_t>(y) * width + x];
  }
};

/// The automatic blend of a viewport config: the coverage of every output
/// whose blend is BlendMode::automatic (outputs with "none", "file" or "mpcdi" take no
/// part: their light is not shared), with what the weights need precomputed
/// (for outputs with pixels without a ray, e.g. a fisheye's corners or the
/// unmapped parts of a warp mesh, the distance of every pixel to the nearest
/// such pixel: an exact Euclidean distance transform).
class AutoBlend {
 public:
  /// Keeps a reference to `config`, which must outlive this object.
  explicit AutoBlend(const ViewportConfig& config);

  /// Number of outputs of the config (participating or not).
  std::size_t size() const { return outputs_.size(); }
  bool participates(std::size_t output) const { return outputs_[output].participates; }

  /// D: the distance in pixels from the continuous position (x, y) of the
  /// output's image to the border of its coverage; 0 outside it.
  double border_distance_px(std::size_t output, double x_px, double y_px) const;
  /// f_j at a pixel position of output j: S(min(1, D / r)).
  double raw_weight_at(std::size_t output, double x_px, double y_px) const;
  /// f_j(d) of a camera-frame direction; 0 where the output does not see it
  /// or does not participate.
  double raw_weight(std::size_t output, const glm::dvec3& direction) const;
  /// w_j(d) for every output j into `weights` (size() values): f_j / Σ f;
  /// all zero where no participating output covers d. Returns Σ_j f_j(d).
  double weights(const glm::dvec3& direction, std::span<double> weights) const;

  /// The mask of one output: w_i at every pixel centre (0 where the pixel has
  /// no ray). Throws std::invalid_argument when the output does not participate.
  BlendMask mask(std::size_t output) const;

 private:
  struct Output {
    const OutputConfig* config = nullptr;
    bool participates = false;
    double ramp_px = 1.0;
    /// Empty when every pixel centre has a ray; else per pixel centre the
    /// distance to the nearest centre without one, minus half a pixel (≥ 0).
    std::vector<float> ray_border_px;
  };

  const ViewportConfig& config_;
  std::vector<Output> outputs_;
};

/// AutoBlend(config).mask(output_index).
BlendMask compute_auto_blend(const ViewportConfig& config, std::size_t output_index);

/// The mask an output's blend source gives, times the warp mesh's intensity
/// where the output has a warp (WarpedProjection::intensity at pixel centres):
/// none → 1, automatic → compute_auto_blend, file → load_blend_mask, mpcdi →
/// the region's alpha map and, where it has one, its beta map as `beta`
/// (sample_mpcdi_blend_map: bilinear at the pixel centres, linear light). Throws
/// what ViewportConfig::require_renderable() throws for an output whose warp,
/// or whose automatic blend partner's warp, is broken.
BlendMask output_blend_mask(const ViewportConfig& config, std::size_t output_index);

/// Reads a mask PNG: α = stored^gamma, stored = integer / (2^bits − 1), channel
/// 0. Throws std::runtime_error naming the file for a file that cannot be read
/// or decoded and for a size other than width_px × height_px.
BlendMask load_blend_mask(const std::filesystem::path& path, double gamma, int width_px, int height_px);

/// The black-level map of an output, one value per pixel (row 0 at the top, x
/// fastest): what the output stage adds to a pixel whatever the picture,
/// P' − P·α·(1 − β) = β. `mask` is the output's (output_blend_mask()): its β
/// map where it has one (an MPCDI region's beta map), else the output's
/// black_level at every pixel, covered or not. It is what a projector applying
/// MPCDI's beta map must add to show what `zenith render --viewport` writes.
std::vector<float> black_level_map(const OutputConfig& output, const BlendMask& mask);

/// The output stage of one display-linear value P (a fraction of full white):
/// P · α · (1 − β) + β.
inline double blend_display_value(double p, double alpha, double black_level) {
  return p * alpha * (1.0 - black_level) + black_level;
}

/// blend_display_value() on `row_count` rows of display-linear RGB (3 floats a
/// pixel, x fastest, mask.width pixels a row) starting at row `first_row` of
/// the mask; β the mask's black_level_at(x, y, black_level). Throws
/// std::invalid_argument when the rows do not fit the mask.
void apply_blend(std::span<float> rgb, int first_row, int row_count, const BlendMask& mask, double black_level);

}  // namespace zenith::warp
