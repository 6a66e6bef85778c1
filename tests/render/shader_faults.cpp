#include "tests/render/shader_faults.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <utility>

#include "tests/render/test_shaders.h"

namespace zenith::render::testing {
namespace {

// maths.glsl's comment at the end of its fp64 elementary functions.
constexpr std::string_view kFp64FunctionsEnd = "// ---- end of the fp64 elementary functions";

/// `text` with tests/shaders/ulp_perturbation.glsl after maths.glsl's
/// insertion point, and a #line that gives the lines after it their numbers
/// again; unchanged where the stage does not include maths.glsl.
std::string with_ulp_perturbation(std::string_view name, std::string text) {
  const std::size_t at = text.find(kFp64FunctionsEnd);
  if (at == std::string::npos) {
    if (text.find("USE_FP64") != std::string::npos && text.find("double exp_r(") != std::string::npos)
      throw std::logic_error(
          fmt::format("shader '{}' defines the fp64 elementary functions without maths.glsl's line '{}' to insert the "
                      "ULP perturbation after",
                      name, kFp64FunctionsEnd));
    return text;
  }
  const std::size_t line_end = text.find('\n', at);
  const std::size_t insert_at = line_end == std::string::npos ? text.size() : line_end + 1;
  // The marker's number: the last #line before it, and the lines since.
  std::string renumber;
  if (const std::size_t directive = text.rfind("\n#line ", at); directive != std::string::npos) {
    int line = 0, file = 0;
    if (std::sscanf(text.c_str() + directive + 1, "#line %d %d", &line, &file) == 2) {
      const auto lines_since = std::count(text.begin() + static_cast<std::ptrdiff_t>(directive) + 1,
                                          text.begin() + static_cast<std::ptrdiff_t>(insert_at), '\n');
      renumber = fmt::format("#line {} {}\n", line + static_cast<int>(lines_since) - 1, file);
    }
  }
  std::string block(test_shader_source("ulp_perturbation.glsl"));
  if (!block.ends_with('\n')) block += '\n';
  text.insert(insert_at, block + renumber);
  return text;
}

std::vector<gl::ShaderDefine> parse_defines(std::string_view list) {
  std::vector<gl::ShaderDefine> parsed;
  while (!list.empty()) {
    const std::string_view item = list.substr(0, list.find(','));
    list.remove_prefix(std::min(list.size(), item.size() + 1));
    const std::size_t equals = item.find('=');
    parsed.push_back({std::string(item.substr(0, equals)),
                      equals == std::string_view::npos ? std::string() : std::string(item.substr(equals + 1))});
  }
  return parsed;
}

std::string environment(const char* variable) {
  const char* value = std::getenv(variable);
  return value == nullptr ? std::string() : std::string(value);
}

}  // namespace

std::string with_shader_faults(const ShaderFaults& faults, std::string_view name, std::string text) {
  std::vector<gl::ShaderDefine> defines = faults.defines;
  if (faults.ulp_perturbation != 0) {
    text = with_ulp_perturbation(name, std::move(text));
    defines.push_back({"ULP_PERTURBATION", std::to_string(faults.ulp_perturbation)});
  }
  std::vector<std::string> lines;
  if (!defines.empty()) {
    // inject_defines checks the names and values; its #line is replaced below.
    const std::string with = gl::inject_defines(name, "#version 450\n", defines);
    for (std::string_view l = with; !l.empty();) {
      const std::string_view line = l.substr(0, l.find('\n'));
      l.remove_prefix(std::min(l.size(), line.size() + 1));
      if (line.starts_with("#define")) lines.emplace_back(line);
    }
  }
  if (!faults.fail_shader.empty() && name == faults.fail_shader)
    lines.push_back(fmt::format("#error {} made to fail by ZENITH_FAIL_SHADER", name));
  if (!faults.fail_shader_c5025.empty() && name == faults.fail_shader_c5025 &&
      text.find(gl::kNvidiaLoopUnrollOff) == std::string::npos)
    lines.push_back(
        fmt::format("#error C5025: {} made to fail as NVIDIA's loop unrolling does by ZENITH_FAIL_SHADER_C5025", name));
  if (lines.empty()) return text;
  return gl::insert_after_version(name, text, lines);
}

ShaderFaults shader_faults_from_environment() {
  ShaderFaults faults;
  faults.defines = parse_defines(environment("ZENITH_SHADER_DEFINES"));
  if (const std::string ulps = environment("ZENITH_ULP_PERTURBATION"); !ulps.empty()) {
    const auto [end, error] = std::from_chars(ulps.data(), ulps.data() + ulps.size(), faults.ulp_perturbation);
    if (error != std::errc() || end != ulps.data() + ulps.size() || std::abs(faults.ulp_perturbation) > 1000)
      throw std::invalid_argument("ZENITH_ULP_PERTURBATION='" + ulps + "': an integer in [-1000, 1000]");
  }
  faults.fail_shader = environment("ZENITH_FAIL_SHADER");
  faults.fail_shader_c5025 = environment("ZENITH_FAIL_SHADER_C5025");
  return faults;
}

ScopedShaderFaults::ScopedShaderFaults(ShaderFaults faults)
    : previous_(gl::install_shader_text_hook([faults = std::move(faults)](std::string_view name, std::string text) {
        return with_shader_faults(faults, name, std::move(text));
      })) {}

ScopedShaderFaults::~ScopedShaderFaults() { gl::install_shader_text_hook(std::move(previous_)); }

}  // namespace zenith::render::testing
