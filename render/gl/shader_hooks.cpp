#include "render/gl/shader_hooks.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "core/sha256.h"

namespace zenith::render::gl {

namespace {

const char* stage_extension(ShaderStage stage) {
  switch (stage) {
    case ShaderStage::vertex: return "vert";
    case ShaderStage::fragment: return "frag";
    case ShaderStage::compute: return "comp";
  }
  return "glsl";
}

/// "render/present.frag" → "render_present.frag": one file name per shader.
std::string flat_name(std::string_view name) {
  std::string out(name);
  for (char& c : out)
    if (c == '/' || c == '\\') c = '_';
  return out;
}

}  // namespace

std::string with_test_hooks(std::string_view name, std::string text) {
  std::vector<std::string> lines;
  if (const char* defines = std::getenv("ZENITH_SHADER_DEFINES"); defines != nullptr && *defines != '\0') {
    std::vector<ShaderDefine> parsed;
    std::string_view rest = defines;
    while (!rest.empty()) {
      const std::string_view item = rest.substr(0, rest.find(','));
      rest.remove_prefix(std::min(rest.size(), item.size() + 1));
      const std::size_t equals = item.find('=');
      parsed.push_back({std::string(item.substr(0, equals)),
                        equals == std::string_view::npos ? std::string() : std::string(item.substr(equals + 1))});
    }
    // inject_defines checks the names and values; its #line is replaced below.
    const std::string with = inject_defines(name, "#version 450\n", parsed);
    for (std::string_view l = with; !l.empty();) {
      const std::string_view line = l.substr(0, l.find('\n'));
      l.remove_prefix(std::min(l.size(), line.size() + 1));
      if (line.starts_with("#define")) lines.emplace_back(line);
    }
  }
  if (const char* target = std::getenv("ZENITH_FAIL_SHADER"); target != nullptr && name == target)
    lines.push_back(fmt::format("#error {} made to fail by ZENITH_FAIL_SHADER", name));
  if (const char* target = std::getenv("ZENITH_FAIL_SHADER_C5025");
      target != nullptr && name == target && text.find(kNvidiaLoopUnrollOff) == std::string::npos)
    lines.push_back(
        fmt::format("#error C5025: {} made to fail as NVIDIA's loop unrolling does by ZENITH_FAIL_SHADER_C5025", name));
  if (lines.empty()) return text;
  return insert_after_version(name, text, lines);
}

void dump_shader_source(std::string_view name, ShaderStage stage, std::string_view text,
                        const std::vector<std::string>& files) {
  const char* dir = std::getenv("ZENITH_SHADER_DUMP_DIR");
  if (dir == nullptr || *dir == '\0') return;
  try {
    const std::filesystem::path folder(dir);
    std::filesystem::create_directories(folder);
    const std::string hash = core::sha256_hex(text.data(), text.size()).substr(0, 16);
    const std::filesystem::path path = folder / fmt::format("{}.{}.{}", flat_name(name), hash, stage_extension(stage));
    if (std::filesystem::exists(path)) return;
    {
      std::ofstream names(path.string() + ".files", std::ios::binary);
      for (const std::string& f : files) names << f << '\n';
    }
    std::ofstream out(path, std::ios::binary);
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    if (!out) throw std::runtime_error("write failed");
  } catch (const std::exception& e) {
    spdlog::warn("ZENITH_SHADER_DUMP_DIR: could not write shader '{}': {}", name, e.what());
  }
}

}  // namespace zenith::render::gl
