#include "render/gl/program_binary_cache.h"

#include <epoxy/gl.h>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <unistd.h>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <functional>
#include <iterator>
#include <system_error>
#include <thread>
#include <vector>

#include "core/sha256.h"

namespace zenith::render::gl {

namespace {

constexpr char kMagic[8] = {'Z', 'P', 'R', 'G', 'B', 'I', 'N', '1'};

std::string gl_string(GLenum name) {
  const auto* s = reinterpret_cast<const char*>(glGetString(name));
  return s ? s : "";
}

}  // namespace

ProgramBinaryCache::ProgramBinaryCache(std::filesystem::path directory)
    : directory_(std::move(directory)),
      driver_(fmt::format("{}\n{}\n{}\n{}\n", gl_string(GL_VENDOR), gl_string(GL_RENDERER), gl_string(GL_VERSION),
                          gl_string(GL_SHADING_LANGUAGE_VERSION))) {
  glGetIntegerv(GL_NUM_PROGRAM_BINARY_FORMATS, &formats_);
  if (formats_ <= 0) spdlog::debug("program binary cache: the driver offers no binary format; programs are compiled");
}

std::string ProgramBinaryCache::key(std::span<const std::string> stage_texts) const {
  std::string all = driver_;
  for (const std::string& t : stage_texts) all += fmt::format("{}\n{}", t.size(), t);
  return core::sha256_hex(all.data(), all.size());
}

unsigned ProgramBinaryCache::load(const std::string& key) {
  const unsigned program = start_load(key);
  return program != 0 && finish_load(key, program) ? program : 0;
}

unsigned ProgramBinaryCache::start_load(const std::string& key) {
  if (!enabled()) return 0;
  const std::filesystem::path path = directory_ / (key + ".bin");
  std::ifstream in(path, std::ios::binary);
  if (!in) return 0;
  const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::uint32_t format = 0;
  const std::size_t header = sizeof kMagic + sizeof format;
  if (bytes.size() <= header || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0) {
    refuse(key, 0);  // not ours, or truncated
    return 0;
  }
  std::memcpy(&format, bytes.data() + sizeof kMagic, sizeof format);
  const GLuint program = glCreateProgram();
  glProgramBinary(program, format, bytes.data() + header, static_cast<GLsizei>(bytes.size() - header));
  return program;
}

bool ProgramBinaryCache::finish_load(const std::string& key, unsigned program) {
  GLint ok = GL_FALSE;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (ok == GL_TRUE) {
    std::lock_guard lock(mutex_);
    ++statistics_.loaded;
    return true;
  }
  refuse(key, program);
  return false;
}

void ProgramBinaryCache::refuse(const std::string& key, unsigned program) {
  // Refused by this driver: compiled instead, and stored anew.
  while (glGetError() != GL_NO_ERROR) {
  }
  if (program != 0) glDeleteProgram(program);
  {
    std::lock_guard lock(mutex_);
    ++statistics_.refused;
  }
  const std::filesystem::path path = directory_ / (key + ".bin");
  std::error_code ec;
  std::filesystem::remove(path, ec);
  spdlog::debug("program binary cache: {} refused; compiling", path.string());
}

void ProgramBinaryCache::store(const std::string& key, unsigned program) {
  if (!enabled()) return;
  GLint length = 0;
  glGetProgramiv(program, GL_PROGRAM_BINARY_LENGTH, &length);
  if (length <= 0) return;
  std::vector<char> binary(static_cast<std::size_t>(length));
  GLenum format = 0;
  GLsizei written = 0;
  glGetProgramBinary(program, length, &written, &format, binary.data());
  if (written <= 0) return;
  try {
    std::filesystem::create_directories(directory_);
    const std::filesystem::path path = directory_ / (key + ".bin");
    const std::filesystem::path temporary =
        directory_ /
        fmt::format("{}.{}.{}.tmp", key, ::getpid(), std::hash<std::thread::id>{}(std::this_thread::get_id()));
    {
      std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
      const auto f = static_cast<std::uint32_t>(format);
      out.write(kMagic, sizeof kMagic);
      out.write(reinterpret_cast<const char*>(&f), sizeof f);
      out.write(binary.data(), written);
      if (!out) throw std::runtime_error("write failed");
    }
    std::filesystem::rename(temporary, path);
    std::lock_guard lock(mutex_);
    ++statistics_.stored;
  } catch (const std::exception& e) {
    std::lock_guard lock(mutex_);
    if (!warned_)
      spdlog::warn("program binary cache in {}: {}; programs are compiled each run", directory_.string(), e.what());
    warned_ = true;
  }
}

}  // namespace zenith::render::gl
