#include "render/display/colour_profile_textures.h"

#include <algorithm>
#include <vector>

namespace zenith::render::display {
namespace {

using gl::Texture;
using gl::TextureFormat;
using Profile = warp::MpcdiColourProfile;

}  // namespace

gl::Texture lut_1d_texture(const warp::CubeLut& lut) {
  const int width = std::min(lut.size, kLut1dRowTexels);
  const int rows = (lut.size + width - 1) / width;
  std::vector<float> rgba(static_cast<std::size_t>(width) * rows * 4, 0.0f);
  for (std::size_t i = 0; i < static_cast<std::size_t>(lut.size); ++i)
    for (std::size_t c = 0; c < 3; ++c) rgba[4 * i + c] = lut.rgb[3 * i + c];
  return Texture::create_2d(TextureFormat::rgba32f, width, rows, rgba);
}

gl::Texture lut_3d_texture(const warp::CubeLut& lut) {
  const std::size_t points = static_cast<std::size_t>(lut.size) * lut.size * lut.size;
  std::vector<float> rgba(points * 4, 0.0f);
  for (std::size_t i = 0; i < points; ++i)
    for (std::size_t c = 0; c < 3; ++c) rgba[4 * i + c] = lut.rgb[3 * i + c];  // red fastest: x, then y, then z
  return Texture::create_3d(TextureFormat::rgba32f, lut.size, lut.size, lut.size, rgba);
}

ColourProfileTextures::ColourProfileTextures(const warp::MpcdiColourProfile& profile)
    : profile_(profile), present_(true) {
  if (profile_.decode.type == Profile::Decode::Type::lut1d) decode_1d_ = lut_1d_texture(*profile_.decode.lut);
  if (profile_.correct.lut) {
    if (profile_.correct.lut->is_3d())
      correct_3d_ = lut_3d_texture(*profile_.correct.lut);
    else
      correct_1d_ = lut_1d_texture(*profile_.correct.lut);
  }
  if (profile_.encode.lut) {
    if (profile_.encode.lut->is_3d())
      encode_3d_ = lut_3d_texture(*profile_.encode.lut);
    else
      encode_1d_ = lut_1d_texture(*profile_.encode.lut);
  }
}

void ColourProfileTextures::set_uniforms(const gl::ShaderProgram& p) const {
  if (!present_) return;
  const Profile& c = profile_;
  p.set_uniform("decode_type", c.decode.type == Profile::Decode::Type::lut1d ? 1 : 0);
  p.set_uniform("decode_gamma", static_cast<float>(c.decode.gamma));
  const int correct_type = c.correct.type == Profile::Correct::Type::none            ? 0
                           : c.correct.type == Profile::Correct::Type::lut1d_primary ? 1
                                                                                     : 2;
  p.set_uniform("correct_type", correct_type);
  p.set_uniform("has_correct_lut_1d", correct_1d_.id() != 0 ? 1 : 0);
  // The primaries matrix, column-major: column j holds (red, green, blue)Primary's j-th entry.
  std::array<float, 9> m{};
  for (std::size_t row = 0; row < 3; ++row)
    for (std::size_t column = 0; column < 3; ++column)
      m[3 * column + row] = static_cast<float>(c.correct.primaries[row][column]);
  p.set_uniform("primaries", m);
  int encode_type = 0;
  if (c.encode.type == Profile::Encode::Type::gamma) encode_type = 1;
  if (c.encode.type == Profile::Encode::Type::lut1d) encode_type = 2;
  if (c.encode.type == Profile::Encode::Type::lut3d) encode_type = 3;
  p.set_uniform("encode_type", encode_type);
  p.set_uniform("encode_inverse_gamma", static_cast<float>(1.0 / c.encode.gamma));
  if (decode_1d_.id() != 0) p.set_uniform("decode_lut_size", c.decode.lut->size);
  if (correct_1d_.id() != 0 || correct_3d_.id() != 0) p.set_uniform("correct_lut_size", c.correct.lut->size);
  if (encode_1d_.id() != 0 || encode_3d_.id() != 0) p.set_uniform("encode_lut_size", c.encode.lut->size);
}

std::array<std::pair<unsigned, const Texture*>, 5> ColourProfileTextures::lut_textures() const {
  const auto held = [](const Texture& t) { return t.id() != 0 ? &t : nullptr; };
  return {{{binding::kDecodeLutUnit, held(decode_1d_)},
           {binding::kCorrectLut1dUnit, held(correct_1d_)},
           {binding::kCorrectLut3dUnit, held(correct_3d_)},
           {binding::kEncodeLut1dUnit, held(encode_1d_)},
           {binding::kEncodeLut3dUnit, held(encode_3d_)}}};
}

}  // namespace zenith::render::display
