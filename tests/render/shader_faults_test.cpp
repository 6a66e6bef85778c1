// The tests' shader faults (tests/render/shader_faults.h) on the text of real
// stages: where the fp64 perturbation lands and what the lines after it are
// numbered, the failures of one named stage, the environment's spelling. No
// GL context; the programs that run with them are in gpu_precompute_test.cpp,
// parameterization_gpu_test.cpp and gl_context_test.cpp.
#include "tests/render/shader_faults.h"

#include <gtest/gtest.h>
#include <stdlib.h>

#include <algorithm>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "render/shader_source.h"
#include "tests/render/test_shaders.h"

namespace zenith::render::testing {
namespace {

/// The 1-based line of maths.glsl that ends its fp64 elementary functions.
int fp64_functions_end_line() {
  const std::string_view maths = shader_source("atmosphere/maths.glsl");
  const std::size_t at = maths.find("// ---- end of the fp64 elementary functions");
  EXPECT_NE(at, std::string_view::npos);
  return 1 + static_cast<int>(std::count(maths.begin(), maths.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
}

TEST(ShaderFaults, ThePerturbationFollowsTheFp64FunctionsAndTheLinesAfterKeepTheirNumbers) {
  const ExpandedShader stage = load_test_shader("test_parameterization.comp");
  const std::string text = with_shader_faults(ShaderFaults::ulps_off(-2), stage.name, stage.text);

  EXPECT_NE(text.find("\n#define ULP_PERTURBATION -2\n"), std::string::npos);
  EXPECT_EQ(stage.text.find("ulps_away"), std::string::npos);
  const std::size_t marker = text.find("// ---- end of the fp64 elementary functions\n");
  const std::size_t block = text.find("double ulps_away(double v)");
  ASSERT_NE(marker, std::string::npos);
  ASSERT_NE(block, std::string::npos);
  EXPECT_LT(marker, block);
  EXPECT_LT(block, text.find("#define sqrt perturbed_sqrt"));
  // The first use of exp_r after maths.glsl's series comes after the #defines that replace it.
  EXPECT_LT(text.find("#define exp_r perturbed_exp"), text.find("real4 exp_r4("));

  const auto maths = std::find(stage.files.begin(), stage.files.end(), "atmosphere/maths.glsl");
  ASSERT_NE(maths, stage.files.end());
  const std::string renumber =
      fmt::format("#endif\n#line {} {}\n", fp64_functions_end_line() + 1, maths - stage.files.begin());
  EXPECT_NE(text.find(renumber, block), std::string::npos) << "expected '" << renumber << "' after the block";
}

TEST(ShaderFaults, AStageWithoutTheFp64FunctionsOnlyGetsTheDefine) {
  const ExpandedShader stage = load_test_shader("test_pattern.comp");
  const std::string text = with_shader_faults(ShaderFaults::ulps_off(1), stage.name, stage.text);
  EXPECT_EQ(text.find("ulps_away"), std::string::npos);
  EXPECT_NE(text.find("#define ULP_PERTURBATION 1"), std::string::npos);
}

TEST(ShaderFaults, Fp64FunctionsWithoutTheInsertionPointAreRefused) {
  const std::string text = "#version 450\n#define USE_FP64 1\ndouble exp_r(double x) { return x; }\n";
  try {
    (void)with_shader_faults(ShaderFaults::ulps_off(1), "moved.comp", text);
    FAIL() << "perturbed a stage without maths.glsl's insertion point";
  } catch (const std::logic_error& e) {
    EXPECT_NE(std::string(e.what()).find("moved.comp"), std::string::npos) << e.what();
  }
}

TEST(ShaderFaults, OnlyTheNamedStageFails) {
  const std::string text = "#version 450\nvoid main() {}\n";
  ShaderFaults faults = ShaderFaults::c5025_in("present.frag");
  faults.fail_shader = "transmittance.comp";
  EXPECT_EQ(with_shader_faults(faults, "direct_irradiance.comp", text), text);
  EXPECT_NE(with_shader_faults(faults, "transmittance.comp", text).find("\n#error transmittance.comp made to fail"),
            std::string::npos);
  EXPECT_NE(with_shader_faults(faults, "present.frag", text).find("#error C5025: present.frag"), std::string::npos);
  // With loop unrolling off, as ShaderBuild's retry builds it, NVIDIA's compiler would accept it.
  const std::string rolled = "#version 450\n" + std::string(gl::kNvidiaLoopUnrollOff) + "\nvoid main() {}\n";
  EXPECT_EQ(with_shader_faults(faults, "present.frag", rolled), rolled);
}

TEST(ShaderFaults, TheEnvironmentSpellsTheSameFaults) {
  setenv("ZENITH_SHADER_DEFINES", "A=1,B", 1);
  setenv("ZENITH_ULP_PERTURBATION", "-1", 1);
  setenv("ZENITH_FAIL_SHADER", "transmittance.comp", 1);
  const ShaderFaults faults = shader_faults_from_environment();
  ASSERT_EQ(faults.defines.size(), 2u);
  EXPECT_EQ(faults.defines[0].name, "A");
  EXPECT_EQ(faults.defines[0].value, "1");
  EXPECT_EQ(faults.defines[1].name, "B");
  EXPECT_EQ(faults.defines[1].value, "");
  EXPECT_EQ(faults.ulp_perturbation, -1);
  EXPECT_EQ(faults.fail_shader, "transmittance.comp");
  setenv("ZENITH_ULP_PERTURBATION", "one", 1);
  try {
    (void)shader_faults_from_environment();
    ADD_FAILURE() << "accepted ZENITH_ULP_PERTURBATION=one";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("ZENITH_ULP_PERTURBATION"), std::string::npos) << e.what();
  }
  for (const char* v : {"ZENITH_SHADER_DEFINES", "ZENITH_ULP_PERTURBATION", "ZENITH_FAIL_SHADER"}) unsetenv(v);
}

}  // namespace
}  // namespace zenith::render::testing
