#pragma once
// One check of a `zenith validate` command: what is checked, against what
// (the measurement's source), whether it held and the figure it found.
#include <string>

namespace zenith::validate {

struct ValidationCheck {
  std::string what, source;
  bool pass = false;
  std::string detail;
};

}  // namespace zenith::validate
