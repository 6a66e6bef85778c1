// What a cluster's frames name of the sky data (astro/sky_data_identity.h):
// the catalogue's identity joined with the Moon's map's, the catalogue's alone
// without a map, a file's SHA-256 or "" when it is missing.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "astro/sky_data_identity.h"
#include "core/sha256.h"

namespace zenith::astro {
namespace {

TEST(SkyDataIdentity, JoinsTheMoonMapToTheCatalogueAndKeepsTheCatalogueAlone) {
  const std::string catalogue(64, 'a'), map(64, 'b');
  EXPECT_EQ(sky_data_identity(catalogue, ""), catalogue);
  const std::string joined = sky_data_identity(catalogue, map);
  const std::string text = catalogue + "\nmoon_map " + map + "\n";
  EXPECT_EQ(joined, core::sha256_hex(text.data(), text.size()));
  EXPECT_NE(joined, sky_data_identity(catalogue, std::string(64, 'c')));
  EXPECT_NE(joined, sky_data_identity(std::string(64, 'd'), map));
}

TEST(SkyDataIdentity, AMapFileIsNamedByTheSha256OfItsBytes) {
  const auto path = std::filesystem::temp_directory_path() / "zenith_sky_data_identity_test.png";
  {
    std::ofstream out(path, std::ios::binary);
    out << "abc";
  }
  // FIPS 180-2's example: SHA-256("abc").
  EXPECT_EQ(moon_map_identity(path), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  std::filesystem::remove(path);
  EXPECT_EQ(moon_map_identity(path), "");
}

}  // namespace
}  // namespace zenith::astro
