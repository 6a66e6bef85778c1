#include "validate/gnuplot.h"

#include <cstdlib>

#include "core/strings.h"

namespace zenith::validate {

bool run_gnuplot(const std::filesystem::path& script) {
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) return false;
  const std::filesystem::path dir = script.parent_path().empty() ? "." : script.parent_path();
  return std::system(
             core::cat("cd '", dir.string(), "' && gnuplot '", script.filename().string(), "' 2>/dev/null").c_str()) ==
         0;
}

}  // namespace zenith::validate
