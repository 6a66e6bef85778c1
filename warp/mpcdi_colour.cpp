#include "warp/mpcdi_colour.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <stdexcept>

namespace zenith::warp {
namespace {

class ColourReader {
 public:
  ColourReader(const std::string& source, const std::string& region_id) : source_(source), region_(region_id) {}

  [[noreturn]] void fail(int line, const std::string& what) const {
    throw std::runtime_error(fmt::format("{}:{}: region '{}': {}", source_, line, region_, what));
  }

  double number(const XmlElement& element, const std::string& what, std::string_view text) const {
    const std::optional<double> value = finite_number(text);
    if (!value) fail(element.line, fmt::format("{} = '{}' is not a finite number", what, std::string(text)));
    return *value;
  }

  /// The type attribute, one of `allowed` (ignoring case), as the list spells it.
  std::string type(const XmlElement& element, std::initializer_list<const char*> allowed) const {
    const std::string* value = element.attribute("type");
    std::string list;
    for (const char* a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
    if (!value) fail(element.line, fmt::format("<{}> has no attribute 'type' ({})", element.name, list));
    for (const char* a : allowed)
      if (equals_ignoring_case(*value, a)) return a;
    fail(element.line, fmt::format("<{}> type '{}': must be one of {}", element.name, *value, list));
  }

  /// The gamma attribute, required for type gamma (§3.5.2), in [kMinColourGamma, kMaxColourGamma].
  double gamma(const XmlElement& element) const {
    const std::string* text = element.attribute("gamma");
    if (!text) fail(element.line, fmt::format("<{}> type 'gamma' has no attribute 'gamma'", element.name));
    const double g = number(element, fmt::format("<{}> attribute 'gamma'", element.name), *text);
    if (!(g >= kMinColourGamma && g <= kMaxColourGamma))
      fail(element.line, fmt::format("<{}> attribute 'gamma' = {}: must be in [{}, {}]", element.name, g,
                                     kMinColourGamma, kMaxColourGamma));
    return g;
  }

  const XmlElement& child(const XmlElement& parent, const char* name) const {
    const XmlElement* c = parent.child(name);
    if (!c) fail(parent.line, fmt::format("<{}> has no <{}>", parent.name, name));
    return *c;
  }

 private:
  const std::string& source_;
  const std::string& region_;
};

/// The lowest colour level (table 3-3) that allows a stage's type.
void require_level(const ColourReader& r, int level, int needed, int line, const std::string& what) {
  if (level != 0 && level < needed)
    r.fail(line,
           fmt::format("{} needs colour level {} or higher (VESA MPCDI v2.0 table 3-3); the file says color=\"{}\"",
                       what, needed, level));
}

}  // namespace

MpcdiColourProfile read_mpcdi_colour(const XmlElement& color, const std::string& source, const std::string& region_id) {
  const ColourReader r(source, region_id);
  using P = MpcdiColourProfile;
  P profile;
  profile.line = color.line;
  // §3.5.2: "Each color tag shall contain a decode and an encode tag."
  const XmlElement& decode = r.child(color, "decode");
  const std::string decode_type = r.type(decode, {"gamma", "lut1d", "none"});
  if (decode_type == "gamma") profile.decode = {P::Decode::Type::gamma, r.gamma(decode), std::nullopt};
  if (decode_type == "lut1d") profile.decode.type = P::Decode::Type::lut1d;  // "none": gamma 1 (§3.5.2)

  // "For cases in which the correct tag is omitted, the correct type attribute will be assumed to be none."
  if (const XmlElement* correct = color.child("correct")) {
    const std::string type = r.type(*correct, {"none", "lut1d-primary", "lut3d"});
    if (type == "lut3d") profile.correct.type = P::Correct::Type::lut3d;
    if (type == "lut1d-primary") {
      profile.correct.type = P::Correct::Type::lut1d_primary;
      if (const XmlElement* primaries = correct->child("primaries")) {
        const char* rows[3] = {"redPrimary", "greenPrimary", "bluePrimary"};
        const char* columns[3] = {"red", "green", "blue"};
        for (std::size_t i = 0; i < 3; ++i) {
          const XmlElement& row = r.child(*primaries, rows[i]);
          for (std::size_t j = 0; j < 3; ++j) {
            const XmlElement& cell = r.child(row, columns[j]);
            profile.correct.primaries[i][j] = r.number(cell, fmt::format("<{}> <{}>", rows[i], columns[j]), cell.text);
          }
        }
      }
    }
  }

  const XmlElement& encode = r.child(color, "encode");
  const std::string encode_type = r.type(encode, {"none", "gamma", "lut1d", "lut3d"});
  if (encode_type == "gamma") profile.encode = {P::Encode::Type::gamma, r.gamma(encode), std::nullopt};
  if (encode_type == "lut1d") profile.encode.type = P::Encode::Type::lut1d;
  if (encode_type == "lut3d") profile.encode.type = P::Encode::Type::lut3d;
  return profile;
}

void attach_mpcdi_colour_luts(MpcdiColourProfile& profile, MpcdiColourLuts luts, int colour_level,
                              const std::string& source, const std::string& region_id) {
  const ColourReader r(source, region_id);
  using P = MpcdiColourProfile;
  const int line = profile.line;
  // Takes the fileset's LUT for a stage that needs one: present, of the right kind.
  const auto take = [&](std::optional<MpcdiColourLut>& lut, const char* element, const char* stage, const char* type,
                        bool want_3d) {
    if (!lut)
      r.fail(line, fmt::format("<color> <{}> type '{}' needs a <{}> in the region's <fileset>", stage, type, element));
    if (lut->lut.is_3d() != want_3d)
      r.fail(lut->line, fmt::format("<{}> '{}' is a {} LUT; <{}> type '{}' needs a {} one", element, lut->path,
                                    lut->lut.is_3d() ? "3D" : "1D", stage, type, want_3d ? "3D" : "1D"));
    std::optional<CubeLut> out = std::move(lut->lut);
    lut.reset();
    return out;
  };

  if (profile.decode.type == P::Decode::Type::lut1d) {
    require_level(r, colour_level, 3, line, "<decode> type 'lut1d'");
    profile.decode.lut = take(luts.decode, "decodeLUT", "decode", "lut1d", false);
  }
  switch (profile.correct.type) {
    case P::Correct::Type::none: break;
    case P::Correct::Type::lut1d_primary:
      // Levels 1 and 2 allow lut1d-primary with primaries only (§3.5.2); the 1D LUT needs level 3.
      if (luts.correct) {
        require_level(r, colour_level, 3, luts.correct->line, "a <correctLUT> (the RGB 1D LUT)");
        profile.correct.lut = take(luts.correct, "correctLUT", "correct", "lut1d-primary", false);
      }
      break;
    case P::Correct::Type::lut3d:
      require_level(r, colour_level, 5, line, "<correct> type 'lut3d'");
      profile.correct.lut = take(luts.correct, "correctLUT", "correct", "lut3d", true);
      break;
  }
  if (profile.encode.type == P::Encode::Type::lut1d) {
    require_level(r, colour_level, 3, line, "<encode> type 'lut1d'");
    profile.encode.lut = take(luts.encode, "encodeLUT", "encode", "lut1d", false);
  }
  if (profile.encode.type == P::Encode::Type::lut3d) {
    require_level(r, colour_level, 5, line, "<encode> type 'lut3d'");
    profile.encode.lut = take(luts.encode, "encodeLUT", "encode", "lut3d", true);
  }
  for (const auto* left : {&luts.decode, &luts.correct, &luts.encode})
    if (*left)
      spdlog::warn("{}:{}: region '{}': LUT '{}' is not used by the region's <color> ({}): ignored", source,
                   (*left)->line, region_id, (*left)->path, describe(profile));
}

}  // namespace zenith::warp
