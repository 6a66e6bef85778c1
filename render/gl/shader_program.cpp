#include "render/gl/shader_program.h"

#include <epoxy/gl.h>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cctype>
#include <map>
#include <optional>
#include <stdexcept>
#include <utility>

#include "render/gl/gl_error.h"
#include "render/gl/program_binary_cache.h"
#include "render/gl/shader_hooks.h"

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

std::vector<std::string_view> split_lines(std::string_view text) {
  std::vector<std::string_view> lines;
  while (!text.empty()) {
    const std::size_t newline = text.find('\n');
    lines.push_back(text.substr(0, newline));
    if (newline == std::string_view::npos) break;
    text.remove_prefix(newline + 1);
  }
  return lines;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

/// The words of a preprocessor directive line ("#line 3 1" → {"line", "3", "1"}), or empty.
std::vector<std::string_view> directive_words(std::string_view line) {
  line = trim(line);
  std::vector<std::string_view> words;
  if (line.empty() || line.front() != '#') return words;
  line.remove_prefix(1);
  while (true) {
    line = trim(line);
    if (line.empty()) break;
    std::size_t end = 0;
    while (end < line.size() && !std::isspace(static_cast<unsigned char>(line[end]))) ++end;
    words.push_back(line.substr(0, end));
    line.remove_prefix(end);
  }
  return words;
}

std::optional<int> parse_int(std::string_view s) {
  if (s.empty() || s.size() > 9) return std::nullopt;
  int v = 0;
  for (char c : s) {
    if (c < '0' || c > '9') return std::nullopt;
    v = v * 10 + (c - '0');
  }
  return v;
}

bool is_identifier(std::string_view s) {
  if (s.empty() || std::isdigit(static_cast<unsigned char>(s.front()))) return false;
  for (char c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return false;
  return true;
}

/// (source-string number, line) → that line's text, following the #line
/// directives of the compiled text.
std::map<std::pair<int, int>, std::string_view> line_map(std::string_view text) {
  std::map<std::pair<int, int>, std::string_view> map;
  int string = 0, line = 1;
  for (std::string_view l : split_lines(text)) {
    const std::vector<std::string_view> words = directive_words(l);
    if (words.size() >= 2 && words[0] == "line") {
      if (auto n = parse_int(words[1])) {
        line = *n;
        if (words.size() >= 3)
          if (auto s = parse_int(words[2])) string = *s;
        continue;
      }
    }
    map.insert_or_assign({string, line}, l);  // later (original) lines win over injected ones
    ++line;
  }
  return map;
}

/// The (source string, line) a compiler message names: "0:7(12): ..." (Mesa),
/// "0(7) : ..." (NVIDIA), "ERROR: 0:7: ..." (others).
std::optional<std::pair<int, int>> message_location(std::string_view message) {
  for (std::string_view prefix : {"ERROR: ", "WARNING: "})
    if (message.substr(0, prefix.size()) == prefix) message.remove_prefix(prefix.size());
  std::size_t i = 0;
  auto digits = [&]() -> std::optional<int> {
    const std::size_t start = i;
    while (i < message.size() && std::isdigit(static_cast<unsigned char>(message[i]))) ++i;
    return parse_int(message.substr(start, i - start));
  };
  const auto string = digits();
  if (!string || i >= message.size()) return std::nullopt;
  const char separator = message[i++];
  if (separator != ':' && separator != '(') return std::nullopt;
  const auto line = digits();
  if (!line || i >= message.size()) return std::nullopt;
  if (separator == '(' && message[i] != ')') return std::nullopt;
  if (separator == ':' && message[i] != '(' && message[i] != ':') return std::nullopt;
  return std::pair{*string, *line};
}

/// The info log with the offending source line under each message that names one.
std::string annotate_log(std::string_view log, std::string_view compiled, const std::vector<std::string>& files) {
  const auto map = line_map(compiled);
  std::string out;
  for (std::string_view message : split_lines(log)) {
    while (!message.empty() && message.back() == '\r') message.remove_suffix(1);
    if (trim(message).empty()) continue;
    out += fmt::format("{}\n", message);
    if (auto where = message_location(message)) {
      const auto [string, line] = *where;
      const std::string file = string >= 0 && static_cast<std::size_t>(string) < files.size()
                                   ? files[static_cast<std::size_t>(string)]
                                   : fmt::format("source {}", string);
      if (auto it = map.find({string, line}); it != map.end())
        out += fmt::format("    {}:{} | {}\n", file, line, trim(it->second));
    }
  }
  if (files.size() > 1) {
    out += "source strings:";
    for (std::size_t k = 0; k < files.size(); ++k)
      out += fmt::format(" {} = {}{}", k, files[k], k + 1 < files.size() ? "," : "");
    out += '\n';
  }
  while (!out.empty() && out.back() == '\n') out.pop_back();
  return out;
}

GLenum stage_enum(ShaderStage stage) {
  switch (stage) {
    case ShaderStage::vertex: return GL_VERTEX_SHADER;
    case ShaderStage::fragment: return GL_FRAGMENT_SHADER;
    case ShaderStage::compute: return GL_COMPUTE_SHADER;
  }
  return GL_COMPUTE_SHADER;
}

std::string shader_log(GLuint shader) {
  GLint length = 0;
  glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<std::size_t>(std::max(length, 0)), '\0');
  if (length > 0) glGetShaderInfoLog(shader, length, nullptr, log.data());
  while (!log.empty() && log.back() == '\0') log.pop_back();
  return log;
}

std::string program_log(GLuint program) {
  GLint length = 0;
  glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<std::size_t>(std::max(length, 0)), '\0');
  if (length > 0) glGetProgramInfoLog(program, length, nullptr, log.data());
  while (!log.empty() && log.back() == '\0') log.pop_back();
  return log;
}

/// Compiles one stage; throws with the annotated log on failure.
GLuint compile(ShaderStage stage, const ShaderCode& code, std::span<const ShaderDefine> defines) {
  const std::string text = with_test_hooks(code.name, inject_defines(code.name, code.text, defines));
  const std::vector<std::string> files = code.files.empty() ? std::vector<std::string>{code.name} : code.files;
  dump_shader_source(code.name, stage, text, files);
  const GLuint shader = glCreateShader(stage_enum(stage));
  if (shader == 0) {
    check_gl_error(fmt::format("shader '{}': glCreateShader", code.name));
    throw std::runtime_error(fmt::format("shader '{}': glCreateShader returned 0", code.name));
  }
  const GLchar* source = text.c_str();
  const GLint length = static_cast<GLint>(text.size());
  glShaderSource(shader, 1, &source, &length);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  const std::string log = shader_log(shader);
  if (ok != GL_TRUE) {
    glDeleteShader(shader);
    throw ShaderBuildError(code.name, fmt::format("shader '{}' ({}) failed to compile:\n{}", code.name,
                                                  to_string(stage), annotate_log(log, text, files)));
  }
  if (!trim(log).empty())
    spdlog::debug("shader '{}' ({}) compiled with messages:\n{}", code.name, to_string(stage), log);
  return shader;
}

/// Links the compiled stages (deleting them); throws with the log on failure.
/// `retrievable`: for glGetProgramBinary (ProgramBinaryCache::store).
GLuint link(const std::string& name, std::span<const GLuint> shaders, bool retrievable = false) {
  const GLuint program = glCreateProgram();
  if (retrievable) glProgramParameteri(program, GL_PROGRAM_BINARY_RETRIEVABLE_HINT, GL_TRUE);
  for (GLuint s : shaders) glAttachShader(program, s);
  glLinkProgram(program);
  for (GLuint s : shaders) {
    glDetachShader(program, s);
    glDeleteShader(s);
  }
  GLint ok = GL_FALSE;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  const std::string log = program_log(program);
  if (ok != GL_TRUE) {
    glDeleteProgram(program);
    throw ShaderBuildError(name, fmt::format("shader program '{}' failed to link:\n{}", name, trim(log)));
  }
  if (!trim(log).empty()) spdlog::debug("shader program '{}' linked with messages:\n{}", name, log);
  return program;
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

namespace {

GLuint build_compute(const ShaderCode& code, std::span<const ShaderDefine> defines, bool retrievable) {
  try {
    const GLuint shader = compile(ShaderStage::compute, code, defines);
    return link(code.name, std::span<const GLuint>(&shader, 1), retrievable);
  } catch (const std::runtime_error& e) {
    if (!is_nvidia_unroll_failure(e.what())) throw;
    // NVIDIA's compiler could not unroll a loop (kNvidiaLoopUnrollOff): the same
    // program again with its loop unrolling off, at every line number unchanged.
    spdlog::info(
        "shader program '{}': NVIDIA's GLSL compiler failed on an unrolled loop (C5025); compiling it "
        "again with loop unrolling off",
        code.name);
    const std::string pragma[] = {std::string(kNvidiaLoopUnrollOff)};
    const ShaderCode rolled{code.name, insert_after_version(code.name, code.text, pragma), code.files};
    const GLuint shader = compile(ShaderStage::compute, rolled, defines);
    return link(code.name, std::span<const GLuint>(&shader, 1), retrievable);
  }
}

}  // namespace

ShaderProgram ShaderProgram::compute(const ShaderCode& code, std::span<const ShaderDefine> defines,
                                     ProgramBinaryCache* binaries) {
  ShaderProgram p;
  std::string key;  // of the binary cache; empty without one
  if (binaries != nullptr && binaries->enabled()) {
    const std::string text[] = {with_test_hooks(code.name, inject_defines(code.name, code.text, defines))};
    key = binaries->key(text);
    p.id_ = binaries->load(key);
  }
  if (p.id_ == 0) {
    p.id_ = build_compute(code, defines, !key.empty());
    if (!key.empty()) binaries->store(key, p.id_);
  }
  p.name_ = code.name;
  p.compute_ = true;
  glGetProgramiv(p.id_, GL_COMPUTE_WORK_GROUP_SIZE, p.local_size_.data());
  return p;
}

ShaderProgram ShaderProgram::graphics(const ShaderCode& vertex, const ShaderCode& fragment,
                                      std::span<const ShaderDefine> defines) {
  const std::string name = vertex.name + " + " + fragment.name;
  const GLuint vs = compile(ShaderStage::vertex, vertex, defines);
  GLuint fs = 0;
  try {
    fs = compile(ShaderStage::fragment, fragment, defines);
  } catch (...) {
    glDeleteShader(vs);
    throw;
  }
  const GLuint shaders[] = {vs, fs};
  ShaderProgram p;
  p.id_ = link(name, shaders);
  p.name_ = name;
  return p;
}

ShaderProgram::~ShaderProgram() { release(); }

ShaderProgram::ShaderProgram(ShaderProgram&& other) noexcept
    : id_(std::exchange(other.id_, 0u)),
      name_(std::move(other.name_)),
      compute_(std::exchange(other.compute_, false)),
      local_size_(std::exchange(other.local_size_, {0, 0, 0})) {}

ShaderProgram& ShaderProgram::operator=(ShaderProgram&& other) noexcept {
  if (this != &other) {
    release();
    id_ = std::exchange(other.id_, 0u);
    name_ = std::move(other.name_);
    compute_ = std::exchange(other.compute_, false);
    local_size_ = std::exchange(other.local_size_, {0, 0, 0});
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
  use();
  glDispatchCompute(groups_x, groups_y, groups_z);
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
