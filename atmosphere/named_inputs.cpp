#include "atmosphere/named_inputs.h"

#include <filesystem>
#include <stdexcept>
#include <system_error>

namespace zenith::atmosphere {

LoadedAtmosphere load_atmosphere_argument(const std::string& value, const LoadOptions& options) {
  std::error_code ec;
  if (std::filesystem::is_regular_file(value, ec) || value.find('/') != std::string::npos || value.ends_with(".json"))
    return load_atmosphere_file(value, options);
  return load_preset(value, options);
}

lut::TableSizes table_sizes_by_name(const std::string& name) {
  if (name == "paper") return lut::TableSizes{};
  if (name == "small") return lut::TableSizes::small();
  if (name == "twilight") {
    lut::TableSizes s;
    s.scattering_mu_s *= 2;
    return s;
  }
  if (name == "large") return lut::TableSizes{512, 128, 128, 32, 64, 256, 64, 16};
  throw std::invalid_argument("unknown table size set '" + name + "': use paper, twilight, small or large");
}

const std::vector<std::string>& table_size_names() {
  static const std::vector<std::string> names = {"paper", "twilight", "small", "large"};
  return names;
}

}  // namespace zenith::atmosphere
