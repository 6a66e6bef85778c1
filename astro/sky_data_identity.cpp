#include "astro/sky_data_identity.h"

#include <fstream>
#include <iterator>
#include <vector>

#include "core/sha256.h"

namespace zenith::astro {

std::string moon_map_identity(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return "";
  const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) return "";
  return core::sha256_hex(bytes.data(), bytes.size());
}

std::string sky_data_identity(const std::string& catalogue_sha256, const std::string& moon_map_sha256) {
  if (moon_map_sha256.empty()) return catalogue_sha256;
  const std::string text = catalogue_sha256 + "\nmoon_map " + moon_map_sha256 + "\n";
  return core::sha256_hex(text.data(), text.size());
}

}  // namespace zenith::astro
