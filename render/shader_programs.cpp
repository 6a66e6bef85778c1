#include "render/shader_programs.h"

#include <string>
#include <vector>

#include "render/shader_bindings.h"

namespace zenith::render {
namespace {

gl::ShaderCode code_from(const ExpandedShader& e) { return gl::ShaderCode{e.name, e.text, e.files}; }

/// The binding points and constants shared with C++ (render/shader_bindings.h), then `defines`.
std::vector<gl::ShaderDefine> with_interface_defines(std::span<const gl::ShaderDefine> defines) {
  std::vector<gl::ShaderDefine> all = shader_interface_defines();
  all.insert(all.end(), defines.begin(), defines.end());
  return all;
}

/// The program's key in a ProgramBuilds: "render/gbuffer.comp PROJECTION_KIND=2 ECLIPSES=0 …".
std::string program_key(std::string_view name, std::span<const gl::ShaderDefine> defines) {
  std::string key(name);
  for (const gl::ShaderDefine& d : defines) key += " " + d.name + "=" + d.value;
  return key;
}

}  // namespace

gl::ShaderProgram compute_program(const ExpandedShader& shader, std::span<const gl::ShaderDefine> defines,
                                  gl::ProgramBinaryCache* binaries) {
  return gl::ShaderProgram::compute(code_from(shader), with_interface_defines(defines), binaries);
}

gl::ShaderBuild start_compute_program(std::string_view name, std::span<const gl::ShaderDefine> defines,
                                      gl::ProgramBinaryCache* binaries) {
  return gl::ShaderBuild::compute(code_from(load_shader(name)), with_interface_defines(defines), binaries);
}

gl::ShaderProgram load_compute_program(std::string_view name, std::span<const gl::ShaderDefine> defines,
                                       gl::ProgramBinaryCache* binaries) {
  return start_compute_program(name, defines, binaries).finish();
}

gl::ShaderBuild start_graphics_program(std::string_view vertex_name, std::string_view fragment_name,
                                       std::span<const gl::ShaderDefine> defines) {
  return gl::ShaderBuild::graphics(code_from(load_shader(vertex_name)), code_from(load_shader(fragment_name)),
                                   with_interface_defines(defines));
}

gl::ShaderProgram load_graphics_program(std::string_view vertex_name, std::string_view fragment_name,
                                        std::span<const gl::ShaderDefine> defines) {
  return start_graphics_program(vertex_name, fragment_name, defines).finish();
}

void start_built_program(gl::ProgramBuilds& builds, std::string_view name, std::span<const gl::ShaderDefine> defines,
                         gl::BuildFor build_for) {
  // The starter may run on another thread after this returns (ProgramBuilds::build_on): it owns its inputs.
  builds.start(
      program_key(name, defines),
      [name = std::string(name), defines = std::vector<gl::ShaderDefine>(defines.begin(), defines.end()),
       binaries = builds.binary_cache()] { return start_compute_program(name, defines, binaries); },
      build_for);
}

bool program_built(const gl::ProgramBuilds& builds, std::string_view name, std::span<const gl::ShaderDefine> defines) {
  return builds.built(program_key(name, defines));
}

const gl::ShaderProgram& built_program(gl::ProgramBuilds& builds, std::string_view name,
                                       std::span<const gl::ShaderDefine> defines) {
  return builds.get(program_key(name, defines),
                    [&] { return start_compute_program(name, defines, builds.binary_cache()); });
}

}  // namespace zenith::render
