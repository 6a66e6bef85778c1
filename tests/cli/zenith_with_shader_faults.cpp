// The zenith command line (apps/command_line.h) with the shader faults its
// environment asks for (tests/render/shader_faults.h: ZENITH_FAIL_SHADER, …):
// how the CLI tests make a driver refuse a program in a child process. A test
// binary; the zenith program has no such switch.
#include <cstdio>
#include <exception>

#include "apps/command_line.h"
#include "tests/render/shader_faults.h"

int main(int argc, char** argv) {
  try {
    const zenith::render::testing::ScopedShaderFaults faults(zenith::render::testing::shader_faults_from_environment());
    return zenith::app::run_command_line(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "zenith_with_shader_faults: %s\n", e.what());
    return 1;
  }
}
