#include "warp/cube_lut.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "warp/xml_reader.h"

namespace zenith::warp {
namespace {

std::string upper(std::string_view text) {
  std::string out(text);
  for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

/// The whitespace-separated words of a line.
std::vector<std::string_view> words(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t k = 0;
  while (k < line.size()) {
    while (k < line.size() && std::isspace(static_cast<unsigned char>(line[k]))) ++k;
    const std::size_t start = k;
    while (k < line.size() && !std::isspace(static_cast<unsigned char>(line[k]))) ++k;
    if (k > start) out.push_back(line.substr(start, k - start));
  }
  return out;
}

/// A finite number that is the whole of `word` (a leading '+' allowed).
std::optional<double> finite(std::string_view word) { return finite_number(word); }

class CubeParser {
 public:
  explicit CubeParser(const std::string& source) : source_(source) {}

  CubeLut parse(std::string_view text) {
    std::size_t start = 0;
    while (start <= text.size()) {
      std::size_t end = text.find('\n', start);
      if (end == std::string_view::npos) end = text.size();
      ++line_;
      std::string_view line = text.substr(start, end - start);
      if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
      read_line(line);
      if (!words(line).empty()) last_content_line_ = line_;
      start = end + 1;
    }
    if (lut_.size == 0) fail_at(last_content_line_, "no LUT_1D_SIZE or LUT_3D_SIZE line: not a .cube LUT");
    const std::size_t expected = expected_rows();
    if (rows_ != expected)
      fail_at(last_content_line_,
              fmt::format("{} rows of data; {} {} needs {}", rows_, size_keyword(), lut_.size, expected));
    return std::move(lut_);
  }

 private:
  [[noreturn]] void fail_at(int line, const std::string& what) const {
    throw std::runtime_error(fmt::format("{}:{}: {}", source_, line, what));
  }
  [[noreturn]] void fail(const std::string& what) const { fail_at(line_, what); }

  const char* size_keyword() const { return lut_.is_3d() ? "LUT_3D_SIZE" : "LUT_1D_SIZE"; }
  std::size_t expected_rows() const {
    const auto n = static_cast<std::size_t>(lut_.size);
    return lut_.is_3d() ? n * n * n : n;
  }

  void read_line(std::string_view line) {
    const std::vector<std::string_view> w = words(line);
    if (w.empty() || w.front().front() == '#') return;
    if (finite(w.front()) || w.front().front() == '-' || w.front().front() == '.' ||
        std::isdigit(static_cast<unsigned char>(w.front().front()))) {
      read_row(w);
      return;
    }
    const std::string keyword = upper(w.front());
    if (rows_ > 0) fail(fmt::format("{}: a keyword after the data rows (the header comes first)", keyword));
    if (keyword == "TITLE") {
      if (title_seen_) fail("TITLE: given twice");
      title_seen_ = true;
      std::string_view rest = line.substr(static_cast<std::size_t>(w.front().data() + w.front().size() - line.data()));
      while (!rest.empty() && std::isspace(static_cast<unsigned char>(rest.front()))) rest.remove_prefix(1);
      while (!rest.empty() && std::isspace(static_cast<unsigned char>(rest.back()))) rest.remove_suffix(1);
      if (rest.size() >= 2 && rest.front() == '"' && rest.back() == '"') rest = rest.substr(1, rest.size() - 2);
      lut_.title = std::string(rest);
    } else if (keyword == "LUT_1D_SIZE" || keyword == "LUT_3D_SIZE") {
      const bool is_3d = keyword == "LUT_3D_SIZE";
      if (lut_.size != 0)
        fail(fmt::format("{}: a second size line (the LUT is already {} {})", keyword, size_keyword(), lut_.size));
      const int lo = is_3d ? kMinCube3dSize : kMinCube1dSize, hi = is_3d ? kMaxCube3dSize : kMaxCube1dSize;
      const std::optional<double> n = w.size() == 2 ? finite(w[1]) : std::nullopt;
      if (!n || *n != std::floor(*n) || *n < lo || *n > hi)
        fail(fmt::format("{} {}: must be an integer in [{}, {}]{}", keyword, w.size() > 1 ? std::string(w[1]) : "", lo,
                         hi, is_3d ? "" : " (VESA MPCDI v2.0 §3.8)"));
      lut_.kind = is_3d ? CubeLut::Kind::lut_3d : CubeLut::Kind::lut_1d;
      lut_.size = static_cast<int>(*n);
      lut_.rgb.reserve(expected_rows() * 3);
    } else if (keyword == "DOMAIN_MIN" || keyword == "DOMAIN_MAX") {
      if (w.size() != 4) fail(fmt::format("{}: needs 3 numbers, has {}", keyword, w.size() - 1));
      check_domain(keyword, {w[1], w[2], w[3]});
    } else if (keyword == "LUT_1D_INPUT_RANGE" || keyword == "LUT_3D_INPUT_RANGE") {
      if (w.size() != 3) fail(fmt::format("{}: needs 2 numbers (min max), has {}", keyword, w.size() - 1));
      check_domain(keyword + " min", {w[1], w[1], w[1]});
      check_domain(keyword + " max", {w[2], w[2], w[2]});
    } else {
      fail(fmt::format("unknown keyword '{}' (TITLE, LUT_1D_SIZE, LUT_3D_SIZE, DOMAIN_MIN, DOMAIN_MAX)",
                       std::string(w.front())));
    }
  }

  /// DOMAIN_MIN must be 0 0 0 and DOMAIN_MAX 1 1 1: MPCDI's nominal input
  /// range is [0, 1]; a larger DOMAIN_MAX is reserved for HDR (§3.8).
  void check_domain(const std::string& keyword, std::array<std::string_view, 3> values) const {
    const bool is_max = keyword.find("MAX") != std::string::npos || keyword.ends_with("max");
    const double want = is_max ? 1.0 : 0.0;
    for (std::size_t c = 0; c < 3; ++c) {
      const std::optional<double> v = finite(values[c]);
      if (!v) fail(fmt::format("{} value {} '{}' is not a number", keyword, c + 1, std::string(values[c])));
      if (*v != want)
        fail(fmt::format("{} value {} = {}: must be {} (VESA MPCDI v2.0 §3.8: the input range is [0, 1]{})", keyword,
                         c + 1, *v, want, is_max ? "; DOMAIN_MAX > 1 is reserved for HDR" : ""));
    }
  }

  void read_row(const std::vector<std::string_view>& w) {
    if (lut_.size == 0) fail("a data row before LUT_1D_SIZE or LUT_3D_SIZE");
    if (rows_ == expected_rows())
      fail(fmt::format("more than the {} rows {} {} needs", expected_rows(), size_keyword(), lut_.size));
    if (w.size() != 3) fail(fmt::format("row {}: {} values, must be 3 (r g b)", rows_ + 1, w.size()));
    static constexpr std::array<const char*, 3> kChannel = {"red", "green", "blue"};
    for (std::size_t c = 0; c < 3; ++c) {
      const std::optional<double> v = finite(w[c]);
      if (!v)
        fail(fmt::format("row {}: {} value '{}' is not a finite number", rows_ + 1, kChannel[c], std::string(w[c])));
      lut_.rgb.push_back(static_cast<float>(*v));
    }
    ++rows_;
  }

  const std::string& source_;
  CubeLut lut_;
  int line_ = 0;
  int last_content_line_ = 0;  // the end of the data, for a short table
  std::size_t rows_ = 0;
  bool title_seen_ = false;
};

}  // namespace

std::array<double, 3> CubeLut::apply(const std::array<double, 3>& input) const {
  const double top = size - 1;
  const auto locate = [top](double x, int& i0, double& t) {
    const double p = std::clamp(std::isnan(x) ? 0.0 : x, 0.0, 1.0) * top;
    i0 = std::min(static_cast<int>(p), static_cast<int>(top) - 1);
    t = p - i0;
  };
  std::array<double, 3> out{};
  if (!is_3d()) {
    for (std::size_t c = 0; c < 3; ++c) {
      int i = 0;
      double t = 0.0;
      locate(input[c], i, t);
      const double a = rgb[3 * static_cast<std::size_t>(i) + c], b = rgb[3 * static_cast<std::size_t>(i + 1) + c];
      out[c] = a + (b - a) * t;
    }
    return out;
  }
  std::array<int, 3> i{};
  std::array<double, 3> t{};
  for (std::size_t c = 0; c < 3; ++c) locate(input[c], i[c], t[c]);
  const auto n = static_cast<std::size_t>(size);
  for (int corner = 0; corner < 8; ++corner) {
    const int dr = corner & 1, dg = (corner >> 1) & 1, db = (corner >> 2) & 1;
    const double weight = (dr ? t[0] : 1.0 - t[0]) * (dg ? t[1] : 1.0 - t[1]) * (db ? t[2] : 1.0 - t[2]);
    const std::size_t k = 3 * (static_cast<std::size_t>(i[0] + dr) +
                               n * (static_cast<std::size_t>(i[1] + dg) + n * static_cast<std::size_t>(i[2] + db)));
    for (std::size_t c = 0; c < 3; ++c) out[c] += weight * rgb[k + c];
  }
  return out;
}

CubeLut parse_cube_lut(std::string_view text, const std::string& source) { return CubeParser(source).parse(text); }

std::string format_cube_lut(const CubeLut& lut) {
  std::string out;
  if (!lut.title.empty()) out += fmt::format("TITLE \"{}\"\n", lut.title);
  out +=
      fmt::format("{} {}\nDOMAIN_MIN 0 0 0\nDOMAIN_MAX 1 1 1\n", lut.is_3d() ? "LUT_3D_SIZE" : "LUT_1D_SIZE", lut.size);
  for (std::size_t k = 0; k + 2 < lut.rgb.size(); k += 3)
    out += fmt::format("{:.9g} {:.9g} {:.9g}\n", lut.rgb[k], lut.rgb[k + 1], lut.rgb[k + 2]);
  return out;
}

}  // namespace zenith::warp
