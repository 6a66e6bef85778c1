#include "render/gl/shader_dump.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

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
