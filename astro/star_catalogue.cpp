#include "astro/star_catalogue.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "astro/geodesic_grid.h"
#include "core/sha256.h"
#include "core/units.h"

namespace zenith::astro {
namespace {

constexpr std::uint32_t kMagic = 0x835f040a;
constexpr std::uint32_t kMagicOtherEndian = 0x0a045f83;
constexpr std::size_t kHeaderBytes = 32;
constexpr std::size_t kStar1Bytes = 28, kStar2Bytes = 10;
constexpr double kMaxPosStar1 = 2147483647.0;  // 2³¹ − 1
constexpr double kMaxPosStar2 = 524287.0;      // 2¹⁹ − 1
// One unit of dx0/dx1: 0.1 mas/yr (ZoneArray.cpp: movementFactor = (π/180)(0.0001/3600)·years / scale).
constexpr double kProperMotionUnit_rad_per_yr = core::kPi / 180.0 * 1e-4 / 3600.0;
constexpr double kRadToMas = 180.0 / core::kPi * 3600.0e3;

std::runtime_error file_error(const std::filesystem::path& path, const std::string& what) {
  return std::runtime_error(path.string() + ": " + what);
}

std::uint32_t u32(const unsigned char* p) {
  return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 | std::uint32_t(p[3]) << 24;
}
std::int32_t i32(const unsigned char* p) { return std::int32_t(u32(p)); }

/// Bits [first, first + count) of a little-endian byte string, as a signed or unsigned field.
std::int64_t bits(const unsigned char* p, int first, int count, bool is_signed) {
  std::uint64_t v = 0;
  for (int b = 0; b < count; ++b) {
    const int bit = first + b;
    v |= std::uint64_t((p[bit >> 3] >> (bit & 7)) & 1u) << b;
  }
  if (is_signed && (v >> (count - 1)) & 1u) return std::int64_t(v) - (std::int64_t(1) << count);
  return std::int64_t(v);
}

/// Position and proper motion from the tangent-plane integers of a zone.
/// q(t) = c + a0 (X0 + D0 t) + a1 (X1 + D1 t) is the (unnormalized) direction
/// t years after J2000; its unit vector p and the rate dp/dt = (dq − p (p·dq)) / |q|
/// projected on the local east and north give μα* and μδ.
void place(CatalogueStar& s, const CatalogueZone& z, double x0, double x1, double d0, double d1) {
  glm::dvec3 q, dq;
  for (int k = 0; k < 3; ++k) {
    q[k] = z.centre[k] + z.axis0[k] * x0 + z.axis1[k] * x1;
    dq[k] = z.axis0[k] * d0 + z.axis1[k] * d1;
  }
  const double n = std::sqrt(glm::dot(q, q));
  const glm::dvec3 p{q[0] / n, q[1] / n, q[2] / n};
  s.dec_rad = std::asin(std::clamp(p[2], -1.0, 1.0));
  s.ra_rad = std::atan2(p[1], p[0]);
  if (s.ra_rad < 0.0) s.ra_rad += 2.0 * core::kPi;
  const double along = glm::dot(p, dq);
  const glm::dvec3 rate{(dq[0] - p[0] * along) / n, (dq[1] - p[1] * along) / n, (dq[2] - p[2] * along) / n};
  const glm::dvec3 east{-std::sin(s.ra_rad), std::cos(s.ra_rad), 0.0};
  const glm::dvec3 north{-std::sin(s.dec_rad) * std::cos(s.ra_rad), -std::sin(s.dec_rad) * std::sin(s.ra_rad),
                         std::cos(s.dec_rad)};
  s.pm_ra_cosdec_mas_yr = glm::dot(rate, east) * kRadToMas;
  s.pm_dec_mas_yr = glm::dot(rate, north) * kRadToMas;
}

std::vector<unsigned char> read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw file_error(path, "cannot open the star catalogue file");
  return std::vector<unsigned char>(std::istreambuf_iterator<char>(in), {});
}

std::vector<CatalogueStar> decode(const std::filesystem::path& path, const std::vector<unsigned char>& bytes,
                                  double magnitude_limit, CatalogueFileHeader& h) {
  if (bytes.size() < kHeaderBytes) throw file_error(path, "shorter than a catalogue header (32 bytes)");
  const std::uint32_t magic = u32(bytes.data());
  if (magic == kMagicOtherEndian)
    throw file_error(path, "a big-endian catalogue file: only the little-endian files of stellarium-data are read");
  if (magic != kMagic) throw file_error(path, "not a Stellarium star catalogue (bad magic number)");
  h.type = u32(&bytes[4]);
  h.major = u32(&bytes[8]);
  h.minor = u32(&bytes[12]);
  h.level = u32(&bytes[16]);
  h.mag_min_millimag = i32(&bytes[20]);
  h.mag_range_millimag = i32(&bytes[24]);
  h.mag_steps = i32(&bytes[28]);
  if (h.type > 1)
    throw file_error(path, "record type " + std::to_string(h.type) +
                               ": only types 0 (Hipparcos, 28 bytes) and 1 (10 bytes) carry proper motion");
  if (h.major != 0) throw file_error(path, "format version " + std::to_string(h.major) + ": only version 0 is known");
  if (h.level > 7) throw file_error(path, "zone level " + std::to_string(h.level) + ": must be in [0, 7]");
  if (h.mag_steps <= 0 || h.mag_range_millimag <= 0)
    throw file_error(path, "magnitude range and steps must be positive");
  const ZoneGrid grid = catalogue_zones(int(h.level));
  const std::size_t zone_count = grid.zones.size();
  const std::size_t record = h.type == 0 ? kStar1Bytes : kStar2Bytes;
  if (bytes.size() < kHeaderBytes + 4 * zone_count) throw file_error(path, "truncated in its zone table");
  std::size_t total = 0;
  for (std::size_t z = 0; z < zone_count; ++z) total += u32(&bytes[kHeaderBytes + 4 * z]);
  const std::size_t first = kHeaderBytes + 4 * zone_count;
  if (total > (bytes.size() - first) / record)
    throw file_error(path, "its zones list " + std::to_string(total) + " stars but it holds " +
                               std::to_string((bytes.size() - first) / record));
  const double scale = grid.gnomonic_extent / (h.type == 0 ? kMaxPosStar1 : kMaxPosStar2);

  std::vector<CatalogueStar> stars;
  const unsigned char* p = &bytes[first];
  for (std::size_t z = 0; z < zone_count; ++z) {
    const std::uint32_t count = u32(&bytes[kHeaderBytes + 4 * z]);
    for (std::uint32_t i = 0; i < count; ++i, p += record) {
      CatalogueStar s;
      double x0, x1, d0, d1;
      int mag_index, bv_index;
      if (h.type == 0) {
        const std::uint32_t id = u32(p);
        s.hip = id & 0xffffffu;
        s.component = std::uint8_t(id >> 24);
        x0 = i32(p + 4), x1 = i32(p + 8);
        bv_index = p[12], mag_index = p[13];
        d0 = i32(p + 16), d1 = i32(p + 20);
        s.parallax_mas = i32(p + 24) * 0.01;
      } else {
        x0 = double(bits(p, 0, 20, true)), x1 = double(bits(p, 20, 20, true));
        d0 = double(bits(p, 40, 14, true)), d1 = double(bits(p, 54, 14, true));
        bv_index = int(bits(p, 68, 7, false)), mag_index = int(bits(p, 75, 5, false));
      }
      s.v_mag = (h.mag_min_millimag + double(mag_index) * h.mag_range_millimag / h.mag_steps) / 1000.0;
      if (s.v_mag > magnitude_limit) continue;
      s.b_minus_v = bv_index * (4.0 / 127.0) - 0.5;
      place(s, grid.zones[z], x0 * scale, x1 * scale, d0 * kProperMotionUnit_rad_per_yr,
            d1 * kProperMotionUnit_rad_per_yr);
      stars.push_back(s);
    }
  }
  return stars;
}

/// stellarium-data's hip_pm.dat: "# HIP pmRA(mas/yr) pmDE(mas/yr)" then one star a line,
/// tab-separated (the Hipparcos new reduction's μα* and μδ, van Leeuwen 2007).
std::vector<std::pair<double, double>> read_hipparcos_proper_motions(const std::filesystem::path& path,
                                                                     const std::string& text) {
  std::vector<std::pair<double, double>> pm;
  std::istringstream in(text);
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    long hip = 0;
    double ra = 0.0, dec = 0.0;
    if (!(fields >> hip >> ra >> dec) || hip <= 0 || hip > 200000 || !std::isfinite(ra) || !std::isfinite(dec))
      throw file_error(path, "line " + std::to_string(number) + ": expected 'HIP pmRA pmDE', got '" + line + "'");
    if (pm.size() <= std::size_t(hip)) pm.resize(std::size_t(hip) + 1, {NAN, NAN});
    pm[std::size_t(hip)] = {ra, dec};
  }
  return pm;
}

}  // namespace

glm::dvec3 equatorial_unit_vector(double ra_rad, double dec_rad) {
  return {std::cos(dec_rad) * std::cos(ra_rad), std::cos(dec_rad) * std::sin(ra_rad), std::sin(dec_rad)};
}

std::vector<CatalogueStar> read_catalogue_file(const std::filesystem::path& path, double magnitude_limit,
                                               CatalogueFileHeader* header) {
  CatalogueFileHeader h;
  auto stars = decode(path, read_bytes(path), magnitude_limit, h);
  if (header) *header = h;
  return stars;
}

StarCatalogue load_star_catalogue(const StarCatalogueOptions& options) {
  if (!(options.magnitude_limit >= -2.0 && options.magnitude_limit <= 10.5))
    throw std::invalid_argument("star catalogue magnitude limit " + std::to_string(options.magnitude_limit) +
                                ": must be in [-2, 10.5]");
  std::vector<std::filesystem::path> candidates;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(options.directory, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("stars_", 0) == 0 && entry.path().extension() == ".cat" && name.find("hip") == std::string::npos)
      candidates.push_back(entry.path());
  }
  if (candidates.empty())
    throw std::runtime_error(options.directory.string() +
                             ": no star catalogue (stars_*.cat); install the Debian package stellarium-data "
                             "(scripts/bootstrap)");
  std::sort(candidates.begin(), candidates.end());

  StarCatalogue catalogue;
  catalogue.magnitude_limit = options.magnitude_limit;
  std::ostringstream identity;
  for (const auto& path : candidates) {
    const std::vector<unsigned char> bytes = read_bytes(path);
    CatalogueFileHeader h;
    if (bytes.size() >= kHeaderBytes && u32(bytes.data()) == kMagic) {
      h.mag_min_millimag = i32(&bytes[20]);
      if (h.brightest_mag() > options.magnitude_limit) continue;  // every star of it is fainter
      h.type = u32(&bytes[4]);
      if (h.type > 1) continue;  // 6-byte records (mag 10.5+): no proper motion, not shipped by Debian
    }
    auto stars = decode(path, bytes, options.magnitude_limit, h);
    catalogue.stars.insert(catalogue.stars.end(), stars.begin(), stars.end());
    catalogue.files.push_back(path);
    identity << path.filename().string() << ' ' << core::sha256_hex(bytes.data(), bytes.size()) << '\n';
  }
  // Proper motions of Hipparcos stars from hip_pm.dat (docs/night-sky.md, "The catalogue":
  // the binary records' own fields, decoded as Stellarium's renderer uses them, are off by
  // up to 20 % and tens of degrees in direction for bright stars).
  const auto pm_path = options.directory / "hip_pm.dat";
  if (options.hipparcos_proper_motions && std::filesystem::exists(pm_path)) {
    const std::vector<unsigned char> bytes = read_bytes(pm_path);
    const auto pm = read_hipparcos_proper_motions(pm_path, std::string(bytes.begin(), bytes.end()));
    for (auto& star : catalogue.stars)
      if (star.hip != 0 && star.hip < pm.size() && !std::isnan(pm[star.hip].first)) {
        star.pm_ra_cosdec_mas_yr = pm[star.hip].first;
        star.pm_dec_mas_yr = pm[star.hip].second;
      }
    catalogue.files.push_back(pm_path);
    identity << pm_path.filename().string() << ' ' << core::sha256_hex(bytes.data(), bytes.size()) << '\n';
  }
  identity << "magnitude_limit " << options.magnitude_limit << '\n';
  const std::string text = identity.str();
  catalogue.identity_sha256 = core::sha256_hex(text.data(), text.size());
  std::stable_sort(catalogue.stars.begin(), catalogue.stars.end(),
                   [](const CatalogueStar& a, const CatalogueStar& b) { return a.v_mag < b.v_mag; });
  return catalogue;
}

}  // namespace zenith::astro
