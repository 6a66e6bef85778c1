// The star catalogue reader (astro/star_catalogue.h): the installed
// stellarium-data files against the Hipparcos catalogue's published places
// (ESA 1997, new reduction van Leeuwen 2007, as SIMBAD gives them at J2000.0),
// and small generated files for the format's edge cases.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <vector>

#include <glm/geometric.hpp>

#include "astro/geodesic_grid.h"
#include "astro/star_catalogue.h"
#include "core/units.h"
#include "tests/scratch_folder.h"

namespace zenith::astro {
namespace {

constexpr double kArcsec = core::kPi / 180.0 / 3600.0;

bool catalogue_installed() { return std::filesystem::exists(kStellariumStarDirectory / "stars_0_0v0_8.cat"); }

#define SKIP_WITHOUT_CATALOGUE()                                                            \
  if (!catalogue_installed())                                                               \
  GTEST_SKIP() << "stellarium-data is not installed (" << kStellariumStarDirectory.string() \
               << "): run scripts/bootstrap as root"

double separation_rad(double ra1, double dec1, double ra2, double dec2) {
  const auto a = equatorial_unit_vector(ra1, dec1), b = equatorial_unit_vector(ra2, dec2);
  const double c[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  return std::atan2(std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]), a[0] * b[0] + a[1] * b[1] + a[2] * b[2]);
}

double hms(double h, double m, double s) { return (h + m / 60.0 + s / 3600.0) * 15.0 * core::kDeg; }
double dms(double d, double m, double s) {
  return (d < 0 || std::signbit(d) ? -1.0 : 1.0) * (std::abs(d) + m / 60.0 + s / 3600.0) * core::kDeg;
}

struct Published {
  std::uint32_t hip;
  double ra_rad, dec_rad, pm_ra_cosdec, pm_dec, v, b_minus_v;
};

// Hipparcos (van Leeuwen 2007) ICRS places at epoch J2000.0 and proper motions; V and B−V of ESA 1997.
const Published kBrightStars[] = {
    {32349, hms(6, 45, 8.91728), dms(-16, 42, 58.0171), -546.01, -1223.07, -1.46, 0.009},  // Sirius
    {91262, hms(18, 36, 56.33635), dms(38, 47, 1.2802), 200.94, 286.23, 0.03, -0.001},     // Vega
    // Arcturus: Hipparcos solved it as a pair (A and a "B" 3.3 mag fainter, since shown not to exist);
    // the file keeps that solution's split of light and colour, so only its place is compared.
    {69673, hms(14, 15, 39.67207), dms(19, 10, 56.6730), -1093.39, -2000.06, NAN, NAN},
    {97649, hms(19, 50, 46.99855), dms(8, 52, 5.9563), 536.23, 385.29, 0.76, 0.221},  // Altair
    {27989, hms(5, 55, 10.30536), dms(7, 24, 25.4304), 27.54, 11.30, 0.45, 1.500},    // Betelgeuse
    {11767, hms(2, 31, 49.09456), dms(89, 15, 50.7923), 44.48, -11.85, 1.97, 0.636},  // Polaris
};

TEST(StarCatalogue, BrightStarsMatchHipparcos) {
  SKIP_WITHOUT_CATALOGUE();
  const StarCatalogue catalogue = load_star_catalogue({});
  for (const Published& p : kBrightStars) {
    SCOPED_TRACE(p.hip);
    const CatalogueStar* found = nullptr;
    for (const auto& s : catalogue.stars)
      if (s.hip == p.hip && s.component <= 1) {
        found = &s;
        break;
      }  // component 1: the primary of a pair
    ASSERT_NE(found, nullptr);
    EXPECT_LT(separation_rad(found->ra_rad, found->dec_rad, p.ra_rad, p.dec_rad) / kArcsec, 0.5);
    EXPECT_NEAR(found->pm_ra_cosdec_mas_yr, p.pm_ra_cosdec, 3.0);
    EXPECT_NEAR(found->pm_dec_mas_yr, p.pm_dec, 3.0);
    // The file's quantization: V in 0.05 mag, B−V in 4/127 mag steps; Hipparcos' V varies by source.
    if (!std::isnan(p.v)) {
      EXPECT_NEAR(found->v_mag, p.v, 0.1);
    }
    if (!std::isnan(p.b_minus_v)) {
      EXPECT_NEAR(found->b_minus_v, p.b_minus_v, 0.1);
    }
  }
}

TEST(StarCatalogue, MagnitudeLimitCountsAndOrder) {
  SKIP_WITHOUT_CATALOGUE();
  const StarCatalogue six = load_star_catalogue({kStellariumStarDirectory, 5.95});
  const StarCatalogue seven = load_star_catalogue({});
  // The Yale Bright Star Catalogue (Hoffleit & Warren 1991) lists 9 110 objects to about V 6.5,
  // ~5 000 of them to V 6.0; Hipparcos' count to V 7.0 is ~15 000 (ESA 1997, vol. 1, §1.2).
  EXPECT_GT(six.stars.size(), 4500u);
  EXPECT_LT(six.stars.size(), 5500u);
  EXPECT_GT(seven.stars.size(), 13000u);
  EXPECT_LT(seven.stars.size(), 17500u);
  for (std::size_t i = 1; i < seven.stars.size(); ++i) ASSERT_LE(seven.stars[i - 1].v_mag, seven.stars[i].v_mag);
  EXPECT_LE(seven.stars.back().v_mag, 7.0);
  EXPECT_EQ(seven.stars.front().hip, 32349u);  // Sirius first
  // The identity: the files' hashes and the limit.
  EXPECT_EQ(seven.identity_sha256.size(), 64u);
  EXPECT_NE(six.identity_sha256, seven.identity_sha256);
  EXPECT_EQ(load_star_catalogue({}).identity_sha256, seven.identity_sha256);
  ASSERT_EQ(six.files.size(), 2u);  // only stars_0 can hold a star of V < 6 (and the proper motions)
  EXPECT_EQ(six.files[0].filename(), "stars_0_0v0_8.cat");
  EXPECT_EQ(six.files[1].filename(), "hip_pm.dat");
}

TEST(StarCatalogue, FaintFileWithTenByteRecords) {
  SKIP_WITHOUT_CATALOGUE();
  const auto path = kStellariumStarDirectory / "stars_3_1v0_4.cat";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " not installed";
  CatalogueFileHeader header;
  const auto stars = read_catalogue_file(path, 10.5, &header);
  EXPECT_EQ(header.type, 1u);
  EXPECT_EQ(header.level, 3u);
  EXPECT_GT(stars.size(), 400000u);
  // What a wrong bit offset would scramble: colours (real stars: median B−V ~0.6, almost none
  // redder than 2), proper motions (median ~10 mas/yr at V 9–10; garbage spreads to ±800),
  // and the Milky Way (|b| < 10°, 17 % of the sky, holds far more than 17 % of the stars).
  const auto pole = equatorial_unit_vector(192.85948 * core::kDeg, 27.12825 * core::kDeg);  // north galactic pole
  std::vector<double> colours, motions;
  std::size_t red = 0, in_plane = 0;
  for (const auto& s : stars) {
    ASSERT_GE(s.v_mag, 9.0);
    ASSERT_LE(s.v_mag, 10.55);
    colours.push_back(s.b_minus_v);
    motions.push_back(std::hypot(s.pm_ra_cosdec_mas_yr, s.pm_dec_mas_yr));
    red += s.b_minus_v > 2.0;
    const auto v = equatorial_unit_vector(s.ra_rad, s.dec_rad);
    in_plane += std::abs(v[0] * pole[0] + v[1] * pole[1] + v[2] * pole[2]) < std::sin(10.0 * core::kDeg);
  }
  std::nth_element(colours.begin(), colours.begin() + colours.size() / 2, colours.end());
  std::nth_element(motions.begin(), motions.begin() + motions.size() / 2, motions.end());
  EXPECT_GT(colours[colours.size() / 2], 0.3);
  EXPECT_LT(colours[colours.size() / 2], 1.0);
  EXPECT_LT(double(red) / stars.size(), 0.02);
  EXPECT_LT(motions[motions.size() / 2], 25.0);
  EXPECT_GT(double(in_plane) / stars.size(), 0.25);
}

// ---- generated files

struct Writer {
  std::vector<unsigned char> bytes;
  void u32(std::uint32_t v) {
    for (int k = 0; k < 4; ++k) bytes.push_back((v >> (8 * k)) & 0xff);
  }
  void header(std::uint32_t type, std::uint32_t level, std::int32_t mag_min, std::int32_t range, std::int32_t steps,
              std::uint32_t magic = 0x835f040a) {
    u32(magic), u32(type), u32(0), u32(8), u32(level), u32(std::uint32_t(mag_min)), u32(std::uint32_t(range)),
        u32(std::uint32_t(steps));
  }
  void star1(std::uint32_t hip, std::uint8_t component, std::int32_t x0, std::int32_t x1, std::uint8_t bv,
             std::uint8_t mag, std::int32_t dx0, std::int32_t dx1, std::int32_t plx) {
    u32(hip | std::uint32_t(component) << 24), u32(std::uint32_t(x0)), u32(std::uint32_t(x1));
    bytes.push_back(bv), bytes.push_back(mag), bytes.push_back(0), bytes.push_back(0);
    u32(std::uint32_t(dx0)), u32(std::uint32_t(dx1)), u32(std::uint32_t(plx));
  }
  /// Star.hpp's Star2 bit fields, packed from bit 0 of an 80-bit little-endian word.
  void star2(std::int32_t x0, std::int32_t x1, std::int32_t dx0, std::int32_t dx1, unsigned bv, unsigned mag) {
    unsigned char w[10] = {};
    int at = 0;
    auto put = [&](std::int64_t value, int count) {
      const std::uint64_t u = std::uint64_t(value) & ((std::uint64_t(1) << count) - 1);
      for (int b = 0; b < count; ++b, ++at)
        if ((u >> b) & 1u) w[at >> 3] |= std::uint8_t(1u << (at & 7));
    };
    put(x0, 20), put(x1, 20), put(dx0, 14), put(dx1, 14), put(bv, 7), put(mag, 5);
    bytes.insert(bytes.end(), w, w + 10);
  }
  std::filesystem::path save(const std::string& name) const {
    const auto path = zenith::testing::process_scratch_folder() / ("astro_" + name);
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    return path;
  }
};

TEST(StarCatalogueFile, ZoneCentreAxesMagnitudeAndColour) {
  Writer w;
  w.header(0, 0, -2000, 12800, 256);
  for (int z = 0; z < 20; ++z) w.u32(z == 7 ? 3 : 0);
  w.star1(42, 0, 0, 0, 16, 10, 0, 0, 1234);                   // at the zone's centre: V = −2 + 10·0.05 = −1.5
  w.star1(43, 2, 1000000000, -500000000, 127, 255, 0, 0, 0);  // off centre; B−V 3.5, V = 10.75 (beyond a 7 limit)
  w.star1(0, 0, -2000000000, 0, 0, 160, 10000, 0, 0);         // V = 6.0; 1 ″/yr along axis 0
  const auto path = w.save("edge.cat");
  const auto stars = read_catalogue_file(path, 7.0);
  ASSERT_EQ(stars.size(), 2u);
  const ZoneGrid grid = catalogue_zones(0);
  const auto& z = grid.zones[7];
  const auto centre = equatorial_unit_vector(stars[0].ra_rad, stars[0].dec_rad);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(centre[k], z.centre[k], 1e-12);
  EXPECT_EQ(stars[0].hip, 42u);
  EXPECT_DOUBLE_EQ(stars[0].v_mag, -1.5);
  EXPECT_NEAR(stars[0].b_minus_v, 16 * 4.0 / 127.0 - 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(stars[0].parallax_mas, 12.34);
  // The third record: −2e9 of 2³¹−1 along axis 0 is a gnomonic offset of −0.93 × the grid's extent;
  // its proper motion, 1000 mas/yr along axis 0 in the tangent plane, shrinks by cos² of the
  // offset angle on the sphere.
  const double t = -2000000000.0 / 2147483647.0 * grid.gnomonic_extent;
  const double expected_pm = 1000.0 / (1.0 + t * t);
  EXPECT_NEAR(std::hypot(stars[1].pm_ra_cosdec_mas_yr, stars[1].pm_dec_mas_yr), expected_pm, 1e-6);
  EXPECT_DOUBLE_EQ(stars[1].v_mag, 6.0);
  EXPECT_NEAR(stars[1].b_minus_v, -0.5, 1e-12);
  EXPECT_EQ(read_catalogue_file(path, 11.0).size(), 3u);
}

TEST(StarCatalogueFile, TenByteRecordsDecodeSignedFields) {
  Writer w;
  w.header(1, 0, 9000, 1500, 30);
  for (int z = 0; z < 20; ++z) w.u32(z == 0 ? 2 : 0);
  w.star2(-524287, 524287, -8192, 8191, 127, 31);
  w.star2(0, 0, 100, -100, 40, 0);
  const auto stars = read_catalogue_file(w.save("star2.cat"), 11.0);
  ASSERT_EQ(stars.size(), 2u);
  EXPECT_DOUBLE_EQ(stars[0].v_mag, 10.55);
  EXPECT_NEAR(stars[0].b_minus_v, 3.5, 1e-12);
  EXPECT_DOUBLE_EQ(stars[1].v_mag, 9.0);
  const ZoneGrid grid = catalogue_zones(0);
  // ±(2¹⁹−1) reach the grid's full gnomonic extent along both axes.
  const auto& z = grid.zones[0];
  const double e = grid.gnomonic_extent;
  double q[3];
  for (int k = 0; k < 3; ++k) q[k] = z.centre[k] - e * z.axis0[k] + e * z.axis1[k];
  const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
  const auto p = equatorial_unit_vector(stars[0].ra_rad, stars[0].dec_rad);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(p[k], q[k] / n, 1e-12);
  // 100 units of 0.1 mas/yr at the zone's centre, along +axis0 and −axis1: |μ| = 10√2 mas/yr.
  EXPECT_NEAR(std::hypot(stars[1].pm_ra_cosdec_mas_yr, stars[1].pm_dec_mas_yr), 10.0 * std::sqrt(2.0), 1e-9);
}

TEST(StarCatalogueFile, BadFilesAreNamedAndExplained) {
  auto message = [](const std::filesystem::path& path) {
    try {
      read_catalogue_file(path, 7.0);
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("/nonexistent/stars.cat").find("cannot open"), std::string::npos);
  Writer bad_magic;
  bad_magic.header(0, 0, 0, 100, 10, 0x12345678);
  EXPECT_NE(message(bad_magic.save("magic.cat")).find("bad magic"), std::string::npos);
  Writer swapped;
  swapped.header(0, 0, 0, 100, 10, 0x0a045f83);
  EXPECT_NE(message(swapped.save("swapped.cat")).find("big-endian"), std::string::npos);
  Writer type2;
  type2.header(2, 0, 0, 100, 10);
  EXPECT_NE(message(type2.save("type2.cat")).find("record type 2"), std::string::npos);
  Writer truncated;
  truncated.header(0, 0, 0, 100, 10);
  for (int z = 0; z < 20; ++z) truncated.u32(5);
  const std::string m = message(truncated.save("truncated.cat"));
  EXPECT_NE(m.find("100 stars but it holds 0"), std::string::npos) << m;
  EXPECT_NE(m.find("truncated.cat"), std::string::npos);
  Writer short_zones;
  short_zones.header(0, 1, 0, 100, 10);
  short_zones.u32(1);
  EXPECT_NE(message(short_zones.save("zones.cat")).find("zone table"), std::string::npos);
  EXPECT_THROW(load_star_catalogue({"/nonexistent", 7.0}), std::runtime_error);
  EXPECT_THROW(load_star_catalogue({kStellariumStarDirectory, 11.0}), std::invalid_argument);
}

TEST(GeodesicGrid, ZonesTileTheSphere) {
  for (int level = 0; level <= 3; ++level) {
    const ZoneGrid g = catalogue_zones(level);
    ASSERT_EQ(g.zones.size(), catalogue_zone_count(level));
    double mean[3] = {};
    for (const auto& z : g.zones) {
      ASSERT_NEAR(glm::dot(z.centre, z.centre), 1.0, 1e-12);
      ASSERT_NEAR(glm::dot(z.axis0, z.axis0), 1.0, 1e-12);
      ASSERT_NEAR(glm::dot(z.axis0, z.centre), 0.0, 1e-12);
      ASSERT_NEAR(glm::dot(z.axis1, z.centre), 0.0, 1e-12);
      ASSERT_NEAR(z.axis0[2], 0.0, 1e-12);  // axis 0 is ẑ × centre: horizontal
      for (int k = 0; k < 3; ++k) mean[k] += z.centre[k] / double(g.zones.size());
    }
    for (double m : mean) EXPECT_NEAR(m, 0.0, 1e-3);  // symmetric cover
  }
  EXPECT_THROW(catalogue_zones(8), std::invalid_argument);
}

}  // namespace
}  // namespace zenith::astro
