#include "render/gl/shader_program.h"

#include <epoxy/gl.h>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cctype>
#include <stdexcept>
#include <utility>

#include "render/gl/glsl_text.h"
#include "render/gl/shader_build.h"

namespace zenith::render::gl {

const char* to_string(ShaderStage stage) {
  switch (stage) {
    case ShaderStage::vertex: return "vertex";
    case ShaderStage::fragment: return "fragment";
    case ShaderStage::compute: return "compute";
  }
  return "?";
}

namespace {

using glsl_text::directive_words;

bool is_identifier(std::string_view s) {
  if (s.empty() || std::isdigit(static_cast<unsigned char>(s.front()))) return false;
  for (char c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return false;
  return true;
}

}  // namespace

std::string insert_after_version(std::string_view name, std::string_view text, std::span<const std::string> lines) {
  std::size_t pos = 0;
  int line = 0;
  while (pos < text.size()) {
    const std::size_t newline = text.find('\n', pos);
    const std::size_t end = newline == std::string_view::npos ? text.size() : newline;
    ++line;
    const std::vector<std::string_view> words = directive_words(text.substr(pos, end - pos));
    if (!words.empty() && words[0] == "version") {
      if (lines.empty()) return std::string(text);
      std::string out(text.substr(0, end));
      out += '\n';
      for (const std::string& l : lines) out += l + '\n';
      out += fmt::format("#line {} 0\n", line + 1);
      if (newline != std::string_view::npos) out.append(text.substr(newline + 1));
      return out;
    }
    if (newline == std::string_view::npos) break;
    pos = newline + 1;
  }
  throw std::invalid_argument(fmt::format("shader '{}' has no #version line", name));
}

std::string inject_defines(std::string_view name, std::string_view text, std::span<const ShaderDefine> defines) {
  std::vector<std::string> lines;
  for (const ShaderDefine& d : defines) {
    if (!is_identifier(d.name) || d.name.substr(0, 3) == "GL_" || d.name.find("__") != std::string::npos)
      throw std::invalid_argument(
          fmt::format("shader '{}': #define name '{}' is not a usable GLSL identifier", name, d.name));
    if (d.value.find_first_of("\r\n") != std::string::npos)
      throw std::invalid_argument(fmt::format("shader '{}': #define {} has a multi-line value", name, d.name));
    lines.push_back(fmt::format("#define {} {}", d.name, d.value));
  }
  return insert_after_version(name, text, lines);
}

bool is_nvidia_unroll_failure(std::string_view message) { return message.find("C5025") != std::string_view::npos; }

ShaderProgram ShaderProgram::compute(const ShaderCode& code, std::span<const ShaderDefine> defines,
                                     ProgramBinaryCache* binaries) {
  return ShaderBuild::compute(code, defines, binaries).finish();
}

ShaderProgram ShaderProgram::graphics(const ShaderCode& vertex, const ShaderCode& fragment,
                                      std::span<const ShaderDefine> defines) {
  return ShaderBuild::graphics(vertex, fragment, defines).finish();
}

ShaderProgram::ShaderProgram(unsigned id, std::string name, bool compute)
    : id_(id), name_(std::move(name)), compute_(compute) {
  if (compute_) glGetProgramiv(id_, GL_COMPUTE_WORK_GROUP_SIZE, local_size_.data());
}

ShaderProgram::~ShaderProgram() { release(); }

ShaderProgram::ShaderProgram(ShaderProgram&& other) noexcept
    : id_(std::exchange(other.id_, 0u)),
      name_(std::move(other.name_)),
      compute_(std::exchange(other.compute_, false)),
      local_size_(std::exchange(other.local_size_, {0, 0, 0})),
      before_first_dispatch_(std::exchange(other.before_first_dispatch_, nullptr)),
      dispatched_(std::exchange(other.dispatched_, false)) {}

ShaderProgram& ShaderProgram::operator=(ShaderProgram&& other) noexcept {
  if (this != &other) {
    release();
    id_ = std::exchange(other.id_, 0u);
    name_ = std::move(other.name_);
    compute_ = std::exchange(other.compute_, false);
    local_size_ = std::exchange(other.local_size_, {0, 0, 0});
    before_first_dispatch_ = std::exchange(other.before_first_dispatch_, nullptr);
    dispatched_ = std::exchange(other.dispatched_, false);
  }
  return *this;
}

void ShaderProgram::release() noexcept {
  if (id_ != 0) glDeleteProgram(id_);
  id_ = 0;
}

void ShaderProgram::use() const { glUseProgram(id_); }

int ShaderProgram::uniform_location(std::string_view uniform) const {
  return glGetUniformLocation(id_, std::string(uniform).c_str());
}

bool ShaderProgram::set_uniform(std::string_view uniform, int value) const {
  const int loc = uniform_location(uniform);
  if (loc >= 0) glProgramUniform1i(id_, loc, value);
  return loc >= 0;
}
bool ShaderProgram::set_uniform(std::string_view uniform, unsigned value) const {
  const int loc = uniform_location(uniform);
  if (loc >= 0) glProgramUniform1ui(id_, loc, value);
  return loc >= 0;
}
bool ShaderProgram::set_uniform(std::string_view uniform, float value) const {
  const int loc = uniform_location(uniform);
  if (loc >= 0) glProgramUniform1f(id_, loc, value);
  return loc >= 0;
}
bool ShaderProgram::set_uniform(std::string_view uniform, const std::array<float, 2>& v) const {
  const int loc = uniform_location(uniform);
  if (loc >= 0) glProgramUniform2fv(id_, loc, 1, v.data());
  return loc >= 0;
}
bool ShaderProgram::set_uniform(std::string_view uniform, const std::array<float, 3>& v) const {
  const int loc = uniform_location(uniform);
  if (loc >= 0) glProgramUniform3fv(id_, loc, 1, v.data());
  return loc >= 0;
}
bool ShaderProgram::set_uniform(std::string_view uniform, const std::array<float, 4>& v) const {
  const int loc = uniform_location(uniform);
  if (loc >= 0) glProgramUniform4fv(id_, loc, 1, v.data());
  return loc >= 0;
}
bool ShaderProgram::set_uniform(std::string_view uniform, const std::array<float, 9>& m) const {
  const int loc = uniform_location(uniform);
  if (loc >= 0) glProgramUniformMatrix3fv(id_, loc, 1, GL_FALSE, m.data());
  return loc >= 0;
}
bool ShaderProgram::set_uniform(std::string_view uniform, const std::array<int, 2>& v) const {
  const int loc = uniform_location(uniform);
  if (loc >= 0) glProgramUniform2iv(id_, loc, 1, v.data());
  return loc >= 0;
}
bool ShaderProgram::set_uniform(std::string_view uniform, const std::array<int, 3>& v) const {
  const int loc = uniform_location(uniform);
  if (loc >= 0) glProgramUniform3iv(id_, loc, 1, v.data());
  return loc >= 0;
}
bool ShaderProgram::set_uniform(std::string_view uniform, const std::array<int, 4>& v) const {
  const int loc = uniform_location(uniform);
  if (loc >= 0) glProgramUniform4iv(id_, loc, 1, v.data());
  return loc >= 0;
}

std::array<int, 3> ShaderProgram::work_group_size() const {
  if (!compute_) throw std::logic_error(fmt::format("shader program '{}' is not a compute program", name_));
  return local_size_;
}

void ShaderProgram::dispatch(unsigned groups_x, unsigned groups_y, unsigned groups_z) const {
  if (!compute_) throw std::logic_error(fmt::format("shader program '{}' is not a compute program", name_));
  if (before_first_dispatch_) std::exchange(before_first_dispatch_, nullptr)();
  dispatched_ = true;
  use();
  glDispatchCompute(groups_x, groups_y, groups_z);
}

void ShaderProgram::draw_triangles(int vertices) const {
  if (compute_) throw std::logic_error(fmt::format("shader program '{}' is a compute program", name_));
  if (before_first_dispatch_) std::exchange(before_first_dispatch_, nullptr)();
  dispatched_ = true;
  use();
  glDrawArrays(GL_TRIANGLES, 0, vertices);
}

void ShaderProgram::dispatch_covering(int width, int height, int depth) const {
  if (width < 1 || height < 1 || depth < 1)
    throw std::invalid_argument(
        fmt::format("shader program '{}': dispatch over {}x{}x{}", name_, width, height, depth));
  const std::array<int, 3> local = work_group_size();
  auto groups = [](int n, int size) { return static_cast<unsigned>((n + size - 1) / size); };
  dispatch(groups(width, local[0]), groups(height, local[1]), groups(depth, local[2]));
}

}  // namespace zenith::render::gl
