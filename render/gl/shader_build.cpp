#include "render/gl/shader_build.h"

#include <epoxy/gl.h>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <stdexcept>
#include <utility>

#include "render/gl/gl_error.h"
#include "render/gl/glsl_text.h"
#include "render/gl/program_binary_cache.h"
#include "render/gl/shader_dump.h"
#include "render/gl/shader_text_hook.h"

namespace zenith::render::gl {

namespace {

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

}  // namespace

bool has_parallel_shader_compile() {
  return epoxy_has_gl_extension("GL_KHR_parallel_shader_compile") ||
         epoxy_has_gl_extension("GL_ARB_parallel_shader_compile");
}

bool set_shader_compiler_threads(unsigned threads) {
  if (epoxy_has_gl_extension("GL_KHR_parallel_shader_compile"))
    glMaxShaderCompilerThreadsKHR(threads);
  else if (epoxy_has_gl_extension("GL_ARB_parallel_shader_compile"))
    glMaxShaderCompilerThreadsARB(threads);
  else
    return false;
  return true;
}

// ---------------------------------------------------------------- start

ShaderBuild ShaderBuild::compute(const ShaderCode& code, std::span<const ShaderDefine> defines,
                                 ProgramBinaryCache* binaries) {
  std::string key;
  if (binaries != nullptr && binaries->enabled()) {
    const std::string text[] = {apply_shader_text_hook(code.name, inject_defines(code.name, code.text, defines))};
    key = binaries->key(text);
    if (const unsigned program = binaries->start_load(key); program != 0) {
      ShaderBuild b;
      b.name_ = code.name;
      b.compute_ = true;
      b.program_ = program;
      b.code_ = code;
      b.defines_.assign(defines.begin(), defines.end());
      b.binaries_ = binaries;
      b.key_ = std::move(key);
      return b;
    }
  }
  ShaderBuild b = start_compute(code, defines, !key.empty());
  if (!key.empty()) {
    b.binaries_ = binaries;
    b.key_ = std::move(key);
  }
  return b;
}

ShaderBuild ShaderBuild::graphics(const ShaderCode& vertex, const ShaderCode& fragment,
                                  std::span<const ShaderDefine> defines) {
  ShaderBuild b;
  b.name_ = vertex.name + " + " + fragment.name;
  b.defines_.assign(defines.begin(), defines.end());
  b.start_stage(ShaderStage::vertex, vertex);  // on a throw, b's destructor deletes what was created
  b.start_stage(ShaderStage::fragment, fragment);
  b.start_link(false);
  return b;
}

ShaderBuild ShaderBuild::start_compute(const ShaderCode& code, std::span<const ShaderDefine> defines,
                                       bool retrievable) {
  ShaderBuild b;
  b.name_ = code.name;
  b.compute_ = true;
  b.code_ = code;
  b.defines_.assign(defines.begin(), defines.end());
  b.start_stage(ShaderStage::compute, code);
  b.start_link(retrievable);
  return b;
}

void ShaderBuild::start_stage(ShaderStage stage, const ShaderCode& code) {
  Stage s{stage, code.name, apply_shader_text_hook(code.name, inject_defines(code.name, code.text, defines_)),
          code.files.empty() ? std::vector<std::string>{code.name} : code.files, 0};
  dump_shader_source(s.name, stage, s.text, s.files);
  s.shader = glCreateShader(stage_enum(stage));
  if (s.shader == 0) {
    check_gl_error(fmt::format("shader '{}': glCreateShader", code.name));
    throw std::runtime_error(fmt::format("shader '{}': glCreateShader returned 0", code.name));
  }
  const GLchar* source = s.text.c_str();
  const GLint length = static_cast<GLint>(s.text.size());
  glShaderSource(s.shader, 1, &source, &length);
  glCompileShader(s.shader);  // no status asked: with parallel compile, this returns at once
  stages_.push_back(std::move(s));
}

void ShaderBuild::start_link(bool retrievable) {
  program_ = glCreateProgram();
  if (program_ == 0) {
    check_gl_error(fmt::format("shader program '{}': glCreateProgram", name_));
    throw std::runtime_error(fmt::format("shader program '{}': glCreateProgram returned 0", name_));
  }
  // For glGetProgramBinary (ProgramBinaryCache::store).
  if (retrievable) glProgramParameteri(program_, GL_PROGRAM_BINARY_RETRIEVABLE_HINT, GL_TRUE);
  for (const Stage& s : stages_) glAttachShader(program_, s.shader);
  // A link may be issued before its stages finished compiling (the extension
  // says so); it waits for them on the driver's side.
  glLinkProgram(program_);
}

// ---------------------------------------------------------------- finish

bool ShaderBuild::ready() const {
  if (!started() || !has_parallel_shader_compile()) return true;
  GLint done = GL_TRUE;
  glGetProgramiv(program_, GL_COMPLETION_STATUS_KHR, &done);
  return done == GL_TRUE;
}

void ShaderBuild::check() {
  // A stage's compile error first: it names the file and line, a link error does not.
  for (const Stage& s : stages_) {
    GLint ok = GL_FALSE;
    glGetShaderiv(s.shader, GL_COMPILE_STATUS, &ok);
    const std::string log = shader_log(s.shader);
    if (ok != GL_TRUE)
      throw ShaderBuildError(name_, fmt::format("shader '{}' ({}) failed to compile:\n{}", s.name, to_string(s.stage),
                                                glsl_text::annotate_log(log, s.text, s.files)));
    if (!glsl_text::trim(log).empty())
      spdlog::debug("shader '{}' ({}) compiled with messages:\n{}", s.name, to_string(s.stage), log);
  }
  GLint ok = GL_FALSE;
  glGetProgramiv(program_, GL_LINK_STATUS, &ok);
  const std::string log = program_log(program_);
  if (ok != GL_TRUE)
    throw ShaderBuildError(name_, fmt::format("shader program '{}' failed to link:\n{}", name_, glsl_text::trim(log)));
  if (!glsl_text::trim(log).empty()) spdlog::debug("shader program '{}' linked with messages:\n{}", name_, log);
  for (Stage& s : stages_) {
    glDetachShader(program_, s.shader);
    glDeleteShader(s.shader);
    s.shader = 0;
  }
  stages_.clear();
}

ShaderProgram ShaderBuild::rebuild(const ShaderCode& code, bool rolled) {
  ShaderBuild again = start_compute(code, defines_, !key_.empty());
  again.binaries_ = binaries_;
  again.key_ = key_;
  again.rolled_ = rolled;
  return again.finish();
}

ShaderProgram ShaderBuild::finish() {
  if (!started()) throw std::logic_error("ShaderBuild::finish: no build was started");
  ShaderBuild self = std::move(*this);  // whatever happens, the GL objects are freed at return
  if (self.stages_.empty()) {
    // Given to glProgramBinary: the binary cache checks it; one the driver
    // refuses is compiled as if it had not been there, and stored anew.
    const unsigned program = std::exchange(self.program_, 0u);
    if (self.binaries_->finish_load(self.key_, program)) return ShaderProgram(program, self.name_, true);
    return self.rebuild(self.code_, false);
  }
  try {
    self.check();
  } catch (const ShaderBuildError& e) {
    if (!self.compute_ || self.rolled_ || !is_nvidia_unroll_failure(e.what())) throw;
    // NVIDIA's compiler could not unroll a loop (kNvidiaLoopUnrollOff): the same
    // program again with its loop unrolling off, at every line number unchanged.
    spdlog::info(
        "shader program '{}': NVIDIA's GLSL compiler failed on an unrolled loop (C5025); compiling it "
        "again with loop unrolling off",
        self.name_);
    const std::string pragma[] = {std::string(kNvidiaLoopUnrollOff)};
    const ShaderCode& code = self.code_;
    return self.rebuild(ShaderCode{code.name, insert_after_version(code.name, code.text, pragma), code.files}, true);
  }
  if (!self.key_.empty()) self.binaries_->store(self.key_, self.program_);
  return ShaderProgram(std::exchange(self.program_, 0u), self.name_, self.compute_);
}

// ---------------------------------------------------------------- lifetime

ShaderBuild::~ShaderBuild() { release(); }

ShaderBuild::ShaderBuild(ShaderBuild&& other) noexcept
    : name_(std::move(other.name_)),
      compute_(other.compute_),
      program_(std::exchange(other.program_, 0u)),
      stages_(std::exchange(other.stages_, {})),
      code_(std::move(other.code_)),
      defines_(std::move(other.defines_)),
      binaries_(std::exchange(other.binaries_, nullptr)),
      key_(std::move(other.key_)),
      rolled_(other.rolled_) {}

ShaderBuild& ShaderBuild::operator=(ShaderBuild&& other) noexcept {
  if (this != &other) {
    release();
    name_ = std::move(other.name_);
    compute_ = other.compute_;
    program_ = std::exchange(other.program_, 0u);
    stages_ = std::exchange(other.stages_, {});
    code_ = std::move(other.code_);
    defines_ = std::move(other.defines_);
    binaries_ = std::exchange(other.binaries_, nullptr);
    key_ = std::move(other.key_);
    rolled_ = other.rolled_;
  }
  return *this;
}

void ShaderBuild::release() noexcept {
  for (const Stage& s : stages_)
    if (s.shader != 0) glDeleteShader(s.shader);
  stages_.clear();
  if (program_ != 0) glDeleteProgram(program_);
  program_ = 0;
}

}  // namespace zenith::render::gl
