#include "render/display/display_encoder.h"

#include <epoxy/gl.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include "render/gl/gl_error.h"
#include "render/shader_bindings.h"
#include "render/shader_programs.h"

namespace zenith::render::display {
namespace {

using gl::TextureFormat;

void check_stage(const OutputStage& stage, int width, int height) {
  if (!(stage.fade.level >= 0.0 && stage.fade.level <= 1.0))
    throw std::invalid_argument(fmt::format("display pass: fade level {} must be in [0, 1]", stage.fade.level));
  for (const double c : stage.fade.colour)
    if (!(c >= 0.0 && c <= 1.0))
      throw std::invalid_argument(fmt::format("display pass: fade colour component {} must be in [0, 1]", c));
  if (!(stage.black_level >= 0.0 && stage.black_level <= 0.5))
    throw std::invalid_argument(fmt::format("display pass: black level {} must be in [0, 0.5]", stage.black_level));
  if (stage.encoding.transfer == image::DisplayEncoding::Transfer::gamma &&
      !(stage.encoding.gamma >= image::kMinDisplayGamma && stage.encoding.gamma <= image::kMaxDisplayGamma))
    throw std::invalid_argument(fmt::format("display pass: gamma {} must be in [{}, {}]", stage.encoding.gamma,
                                            image::kMinDisplayGamma, image::kMaxDisplayGamma));
  if (stage.blend_mask != nullptr &&
      ((stage.blend_mask->format() != TextureFormat::r32f && stage.blend_mask->format() != TextureFormat::rg32f) ||
       stage.blend_mask->is_3d() || stage.blend_mask->width() != width || stage.blend_mask->height() != height))
    throw std::invalid_argument(
        fmt::format("display pass: the blend mask is a {} {}x{} texture; it must be r32f or rg32f of the frame's size "
                    "{}x{}",
                    gl::to_string(stage.blend_mask->format()), stage.blend_mask->width(), stage.blend_mask->height(),
                    width, height));
}

}  // namespace

gl::Texture blend_mask_texture(const warp::BlendMask& mask) {
  if (mask.beta.empty()) return gl::Texture::create_2d(TextureFormat::r32f, mask.width, mask.height, mask.alpha);
  std::vector<float> alpha_beta(2 * mask.alpha.size());
  for (std::size_t i = 0; i < mask.alpha.size(); ++i) {
    alpha_beta[2 * i] = mask.alpha[i];
    alpha_beta[2 * i + 1] = mask.beta.at(i);
  }
  return gl::Texture::create_2d(TextureFormat::rg32f, mask.width, mask.height, alpha_beta);
}

std::array<int, 2> thumbnail_size(int width_px, int height_px, int edge_px) {
  if (width_px < 1 || height_px < 1 || edge_px < 1)
    throw std::invalid_argument(
        fmt::format("thumbnail of a {}x{} frame, edge {} px: sizes must be ≥ 1", width_px, height_px, edge_px));
  const double scale = std::min(1.0, static_cast<double>(edge_px) / std::max(width_px, height_px));
  return {std::max(1, static_cast<int>(std::lround(width_px * scale))),
          std::max(1, static_cast<int>(std::lround(height_px * scale)))};
}

std::vector<std::pair<unsigned, const gl::Texture*>> DisplayEncoder::stage_textures(const OutputStage& stage) {
  if (unused_2d_.id() == 0) {
    const std::vector<float> zero(4, 0.0f);
    unused_2d_ = gl::Texture::create_2d(TextureFormat::rgba32f, 1, 1, zero);
    unused_3d_ = gl::Texture::create_3d(TextureFormat::rgba32f, 1, 1, 1, zero);
  }
  const bool mask = stage.blended && stage.blend_mask != nullptr;
  std::vector<std::pair<unsigned, const gl::Texture*>> textures = {
      {binding::kBlendMaskUnit, mask ? stage.blend_mask : &unused_2d_}};
  const bool profile = stage.colour != nullptr && !stage.colour->empty();
  const ColourProfileTextures none;
  for (const auto& [unit, lut] : (profile ? *stage.colour : none).lut_textures()) {
    const bool three_d = unit == binding::kCorrectLut3dUnit || unit == binding::kEncodeLut3dUnit;
    textures.emplace_back(unit, lut != nullptr ? lut : three_d ? &unused_3d_ : &unused_2d_);
  }
  return textures;
}

gl::DispatchShapes DisplayEncoder::stage_shapes(const OutputStage& stage) {
  gl::DispatchShapes shapes;
  for (const auto& [unit, texture] : stage_textures(stage))
    shapes.sampled[{static_cast<int>(unit), texture->shape().kind}] = texture->shape();
  return shapes;
}

void DisplayEncoder::set_stage(const gl::ShaderProgram& p, int width, int height, const OutputStage& stage) {
  check_stage(stage, width, height);
  p.set_uniform("tone_mapping", stage.tone == image::ToneMapping::clamp ? 1 : 0);
  p.set_uniform("output_stage", stage.blended ? 1 : 0);
  const bool mask = stage.blended && stage.blend_mask != nullptr;
  p.set_uniform("has_blend_mask", mask ? 1 : 0);
  p.set_uniform("has_black_level_map", mask && stage.blend_mask->format() == TextureFormat::rg32f ? 1 : 0);
  p.set_uniform("black_level", static_cast<float>(stage.black_level));
  p.set_uniform("fade_level", static_cast<float>(stage.fade.level));
  p.set_uniform("fade_colour",
                std::array<float, 3>{static_cast<float>(stage.fade.colour[0]), static_cast<float>(stage.fade.colour[1]),
                                     static_cast<float>(stage.fade.colour[2])});
  const bool gamma = stage.encoding.transfer == image::DisplayEncoding::Transfer::gamma;
  p.set_uniform("transfer", gamma ? 1 : 0);
  p.set_uniform("inverse_gamma", static_cast<float>(gamma ? 1.0 / stage.encoding.gamma : 1.0));
  if (stage.colour != nullptr) stage.colour->set_uniforms(p);  // a program with COLOUR_PROFILE 1
  for (const auto& [unit, texture] : stage_textures(stage)) texture->bind(unit);
}

gl::ShaderProgram& DisplayEncoder::encode_program(bool from_band, const OutputStage& stage) {
  const bool profile = stage.colour != nullptr && !stage.colour->empty();
  gl::ShaderProgram& program = encode_programs_[(from_band ? 2 : 0) + (profile ? 1 : 0)];
  if (program.id() == 0) {
    const std::vector<gl::ShaderDefine> defines = {{"FROM_BAND", from_band ? "1" : "0"},
                                                   {"COLOUR_PROFILE", profile ? "1" : "0"}};
    program = load_graphics_program("render/present.vert", "render/display_encode.frag", defines);
  }
  return program;
}

void DisplayEncoder::encode(const gl::Texture& radiance, const OutputStage& stage, gl::Texture& display) {
  if ((display.format() != TextureFormat::rgba8 && display.format() != TextureFormat::rgba16) || display.is_3d() ||
      display.width() != radiance.width() || display.height() != radiance.height())
    throw std::invalid_argument(fmt::format(
        "display pass: the target is a {} {}x{} texture; it must be rgba8 or rgba16 of the frame's size {}x{}",
        gl::to_string(display.format()), display.width(), display.height(), radiance.width(), radiance.height()));
  const gl::ShaderProgram& p = encode_program(false, stage);
  set_stage(p, radiance.width(), radiance.height(), stage);
  radiance.bind(binding::kDisplayRadianceUnit);
  draw_rows(p, display, 0, display.height());
}

void DisplayEncoder::encode_band(const GpuBand& band, const OutputStage& stage, gl::Texture& display) {
  if ((display.format() != TextureFormat::rgba8 && display.format() != TextureFormat::rgba16) || display.is_3d() ||
      display.width() != band.width || band.first_row < 0 || band.rows < 1 ||
      band.first_row + band.rows > display.height())
    throw std::invalid_argument(fmt::format(
        "display pass: the target is a {} {}x{} texture; rows {}+{} of a {}-pixel-wide band do not fit it (rgba8 or "
        "rgba16 of the frame's size)",
        gl::to_string(display.format()), display.width(), display.height(), band.first_row, band.rows, band.width));
  const gl::ShaderProgram& p = encode_program(true, stage);
  set_stage(p, display.width(), display.height(), stage);
  set_band_uniforms(p, band);
  draw_rows(p, display, band.first_row, band.rows);
}

void DisplayEncoder::warm_band(gl::FirstDispatchWarmup& warmup, const OutputStage& stage, const gl::Texture& display) {
  warmup.warm_draw(encode_program(true, stage), stage_shapes(stage), display.format());
}

void DisplayEncoder::warm_encode(gl::FirstDispatchWarmup& warmup, const gl::Texture& radiance, const OutputStage& stage,
                                 const gl::Texture& display) {
  gl::DispatchShapes shapes = stage_shapes(stage);
  shapes.sampled[{static_cast<int>(binding::kDisplayRadianceUnit), radiance.shape().kind}] = radiance.shape();
  warmup.warm_draw(encode_program(false, stage), shapes, display.format());
}

void DisplayEncoder::draw_rows(const gl::ShaderProgram& p, gl::Texture& display, int first_row, int rows) {
  p.set_uniform("code_max", display.format() == TextureFormat::rgba8 ? 255.0f : 65535.0f);
  rows_.bind(display, first_row, rows);
  rows_.draw(p);
  rows_.unbind();
  gl::check_gl_error("display pass");
}

ThumbnailMeans DisplayEncoder::thumbnail(const gl::Texture& radiance, const OutputStage& stage, int edge_px) {
  if (edge_px < 1 || edge_px > kMaxThumbnailEdgePx)
    throw std::invalid_argument(fmt::format("thumbnail edge {} px: must be in [1, {}]", edge_px, kMaxThumbnailEdgePx));
  const auto [tw, th] = thumbnail_size(radiance.width(), radiance.height(), edge_px);
  if (thumbnail_program_.id() == 0) {
    const std::vector<gl::ShaderDefine> defines = {{"COLOUR_PROFILE", "0"}};  // its means need no profile
    thumbnail_program_ = load_compute_program("render/display_thumbnail.comp", defines);
  }
  if (thumbnail_target_.id() == 0 || thumbnail_target_.width() != tw || thumbnail_target_.height() != th)
    thumbnail_target_ = gl::Texture::create_2d(TextureFormat::rgba32f, tw, th);
  const gl::ShaderProgram& p = thumbnail_program_;
  set_stage(p, radiance.width(), radiance.height(), stage);
  radiance.bind(binding::kDisplayRadianceUnit);
  p.set_uniform("frame_size", std::array<int, 2>{radiance.width(), radiance.height()});
  p.set_uniform("thumbnail_size", std::array<int, 2>{tw, th});
  thumbnail_target_.bind_image(binding::kOutputImage, gl::ImageAccess::write_only);
  p.dispatch_covering(tw, th);
  const std::vector<float> rgba = thumbnail_target_.read();  // barrier included; tw · th ≤ 64² pixels
  ThumbnailMeans t{tw, th, std::vector<float>(static_cast<std::size_t>(tw) * th * 3)};
  for (std::size_t i = 0; i < static_cast<std::size_t>(tw) * th; ++i)
    for (std::size_t c = 0; c < 3; ++c) t.rgb[3 * i + c] = rgba[4 * i + c];
  return t;
}

}  // namespace zenith::render::display
