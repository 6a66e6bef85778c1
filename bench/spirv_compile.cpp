#include "bench/spirv_compile.h"

#include <epoxy/gl.h>
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

namespace zenith::bench {
namespace {

std::vector<char> read_bytes(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + file.string());
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

/// A linked program of `shader` (compiled or specialized), or a throw naming `file`.
GLuint link(GLuint shader, const std::filesystem::path& file, const char* what) {
  GLint compiled = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &compiled);
  const GLuint program = glCreateProgram();
  glAttachShader(program, shader);
  glLinkProgram(program);
  GLint linked = GL_FALSE;
  glGetProgramiv(program, GL_LINK_STATUS, &linked);
  glDeleteShader(shader);
  if (compiled != GL_TRUE || linked != GL_TRUE) {
    std::string log(4096, '\0');
    glGetProgramInfoLog(program, static_cast<GLsizei>(log.size()), nullptr, log.data());
    glDeleteProgram(program);
    throw std::runtime_error(fmt::format("{}: the {} program did not build: {}", file.string(), what, log.c_str()));
  }
  return program;
}

/// One dispatch of one work group, to its end: llvmpipe generates the program's code here.
double first_dispatch_ms(GLuint program) {
  const auto start = std::chrono::steady_clock::now();
  glUseProgram(program);
  glDispatchCompute(1, 1, 1);
  glFinish();
  glUseProgram(0);
  return ms_since(start);
}

}  // namespace

bool has_gl_spirv() { return epoxy_has_gl_extension("GL_ARB_gl_spirv"); }

CompileTimes time_glsl_and_spirv(const std::filesystem::path& glsl, const std::filesystem::path& spirv, int rounds,
                                 bool dispatch) {
  const std::vector<char> text = read_bytes(glsl);
  const std::vector<char> binary = read_bytes(spirv);
  std::vector<double> glsl_build, spirv_build, glsl_dispatch, spirv_dispatch;
  for (int r = 0; r < rounds; ++r) {
    const std::string round_text = std::string(text.begin(), text.end()) + fmt::format("\n// round {}\n", r);
    auto start = std::chrono::steady_clock::now();
    GLuint shader = glCreateShader(GL_COMPUTE_SHADER);
    const char* source = round_text.c_str();
    glShaderSource(shader, 1, &source, nullptr);
    glCompileShader(shader);
    GLuint program = link(shader, glsl, "GLSL");
    glsl_build.push_back(ms_since(start));
    glsl_dispatch.push_back(dispatch ? first_dispatch_ms(program) : 0.0);
    glDeleteProgram(program);

    start = std::chrono::steady_clock::now();
    shader = glCreateShader(GL_COMPUTE_SHADER);
    glShaderBinary(1, &shader, GL_SHADER_BINARY_FORMAT_SPIR_V_ARB, binary.data(), static_cast<GLsizei>(binary.size()));
    glSpecializeShaderARB(shader, "main", 0, nullptr, nullptr);
    program = link(shader, spirv, "SPIR-V");
    spirv_build.push_back(ms_since(start));
    spirv_dispatch.push_back(dispatch ? first_dispatch_ms(program) : 0.0);
    glDeleteProgram(program);
  }
  return {median(glsl_build),     median(spirv_build), median(glsl_dispatch),
          median(spirv_dispatch), glsl_build.front(),  spirv_build.front()};
}

}  // namespace zenith::bench
