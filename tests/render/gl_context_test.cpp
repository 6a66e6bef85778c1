// The GL foundation: a headless EGL context, the RAII wrappers, embedded shaders
// with #include, #define variants, compile errors. Runs on Mesa llvmpipe (CPU).
#include <epoxy/gl.h>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <future>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <unistd.h>

#include "render/gl/buffer.h"
#include "render/gl/egl_context.h"
#include "render/gl/fence.h"
#include "render/gl/first_dispatch_warmup.h"
#include "render/gl/gl_error.h"
#include "render/gl/gl_limits.h"
#include "render/gl/program_binary_cache.h"
#include "render/gl/program_builds.h"
#include "render/gl/shader_build.h"
#include "render/gl/shader_program.h"
#include "render/gl/software_rasterizer.h"
#include "render/gl/texture.h"
#include "render/gl/upload_stream.h"
#include "render/shader_bindings.h"
#include "render/shader_programs.h"
#include "render/shader_source.h"
#include "tests/render/shader_faults.h"
#include "tests/render/test_shaders.h"

namespace zenith::render {
namespace {

using gl::HeadlessContext;
using gl::ShaderProgram;
using gl::Texture;
using gl::TextureFormat;

/// The pattern of tests/shaders/test_common.glsl, in C++.
std::vector<float> expected_pattern(int w, int h, int d, float scale = 1.0f, bool index_term = true) {
  std::vector<float> out;
  for (int z = 0; z < d; ++z)
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        out.push_back((static_cast<float>(x) + 0.5f) / static_cast<float>(w) * scale);
        out.push_back((static_cast<float>(y) + 0.5f) / static_cast<float>(h) * scale);
        out.push_back((static_cast<float>(z) + 0.5f) / static_cast<float>(d) * scale);
        out.push_back(index_term ? static_cast<float>(x + w * (y + h * z)) : 0.0f);
      }
  return out;
}

std::vector<float> run_pattern(const ShaderProgram& program, int w, int h, int d) {
  Texture image = Texture::create_3d(TextureFormat::rgba32f, w, h, d);
  image.bind_image(binding::kOutputImage, gl::ImageAccess::write_only);
  program.dispatch_covering(w, h, d);
  std::vector<float> out = image.read();
  gl::check_gl_error("test pattern dispatch");
  return out;
}

void expect_floats_near(const std::vector<float>& actual, const std::vector<float>& expected, float tolerance) {
  ASSERT_EQ(actual.size(), expected.size());
  for (std::size_t i = 0; i < actual.size(); ++i)
    ASSERT_NEAR(actual[i], expected[i], tolerance)
        << "float " << i << " (texel " << i / 4 << ", channel " << i % 4 << ")";
}

class GlTest : public ::testing::Test {
 protected:
  HeadlessContext context_;
};

TEST(SoftwareRasterizer, TwiceTheCpusUpToEightAndTheUsersChoiceKept) {
  EXPECT_EQ(gl::software_rasterizer_threads_for(1), 2);
  EXPECT_EQ(gl::software_rasterizer_threads_for(2), 4);
  EXPECT_EQ(gl::software_rasterizer_threads_for(8), 16);
  EXPECT_EQ(gl::software_rasterizer_threads_for(9), std::nullopt);  // Mesa's default on larger machines
  EXPECT_EQ(gl::software_rasterizer_threads_for(0), std::nullopt);  // unknown CPU count
  // Once a context exists, LP_NUM_THREADS is the user's or ours, and the answer says which.
  const gl::HeadlessContext context;
  const std::string setting = gl::default_software_rasterizer_threads();
  const char* value = std::getenv("LP_NUM_THREADS");
  if (const auto ours = gl::software_rasterizer_threads_for(std::thread::hardware_concurrency())) {
    ASSERT_NE(value, nullptr);
    EXPECT_TRUE(setting == std::string(value) + " (set by zenith)" ||
                setting == std::string(value) + " (LP_NUM_THREADS)")
        << setting;
  } else if (value == nullptr) {
    EXPECT_EQ(setting, "Mesa's default");
  }
  EXPECT_EQ(gl::default_software_rasterizer_threads(), setting) << "decided once per process";
}

TEST(HeadlessContext, CreatesAGl45CoreContextWithoutADisplay) {
  const auto start = std::chrono::steady_clock::now();
  HeadlessContext context;
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();

  EXPECT_TRUE(context.is_current());
  EXPECT_TRUE(context.core_profile());
  EXPECT_TRUE(context.gl_major() > 4 || (context.gl_major() == 4 && context.gl_minor() >= 5))
      << context.gl_major() << "." << context.gl_minor();
  EXPECT_FALSE(context.renderer().empty());
  EXPECT_FALSE(context.vendor().empty());
  // Mesa names the profile in GL_VERSION ("4.5 (Core Profile) Mesa 22.3.6"); NVIDIA does
  // not ("4.5.0 NVIDIA 580.159.04"): the profile mask below is what GL defines.
  if (context.version().find("Mesa") != std::string::npos) {
    EXPECT_NE(context.version().find("Core Profile"), std::string::npos) << context.version();
  }

  GLint profile = 0;
  glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
  EXPECT_TRUE(profile & GL_CONTEXT_CORE_PROFILE_BIT);

  const gl::GlLimits limits = gl::query_gl_limits();
  EXPECT_GE(limits.max_3d_texture_size, 2048);                 // the GL 4.5 minimum
  EXPECT_GE(limits.max_compute_work_group_invocations, 1024);  // the GL 4.3+ minimum
  gl::check_gl_error("query_gl_limits");

  std::printf(
      "renderer: %s\nvendor: %s\nversion: %s\nGLSL: %s\nsource: %s\nEGL: %s %s\nsoftware: %s, surfaceless: %s\n"
      "context creation: %.1f ms\n%s",
      context.renderer().c_str(), context.vendor().c_str(), context.version().c_str(), context.glsl_version().c_str(),
      context.source().c_str(), context.egl_vendor().c_str(), context.egl_version().c_str(),
      context.is_software() ? "yes" : "no", context.surfaceless() ? "yes" : "no", ms, gl::to_string(limits).c_str());
  RecordProperty("renderer", context.renderer());
  RecordProperty("context_creation_ms", std::to_string(ms));
}

TEST(HeadlessContext, MovesAndReleasesOnDestruction) {
  std::optional<HeadlessContext> a(std::in_place);
  ASSERT_TRUE(a->is_current());
  HeadlessContext b(std::move(*a));
  EXPECT_FALSE(a->is_current());  // moved-from: no context
  EXPECT_TRUE(b.is_current());
  EXPECT_THROW(a->make_current(), std::logic_error);
  a.reset();
  EXPECT_TRUE(b.is_current());  // destroying the moved-from object changes nothing
  {
    HeadlessContext c;  // a second context, current now
    EXPECT_TRUE(c.is_current());
    EXPECT_FALSE(b.is_current());
    b.make_current();
    EXPECT_TRUE(b.is_current());
  }  // c was not current: b stays current
  EXPECT_TRUE(b.is_current());
  const Texture t = Texture::create_2d(TextureFormat::r32f, 2, 2, std::vector<float>{1, 2, 3, 4});
  EXPECT_EQ(t.read(), (std::vector<float>{1, 2, 3, 4}));
}

TEST(HeadlessContext, TwoContextsOnTwoThreads) {
  HeadlessContext main_context;
  std::string other_renderer;
  std::thread worker([&] {
    HeadlessContext worker_context;
    const Texture t = Texture::create_2d(TextureFormat::r32f, 1, 1, std::vector<float>{7.0f});
    if (t.read() == std::vector<float>{7.0f}) other_renderer = worker_context.renderer();
  });
  worker.join();
  EXPECT_EQ(other_renderer, main_context.renderer());
  EXPECT_TRUE(main_context.is_current());
}

TEST(HeadlessContext, DevicePreference) {
  EXPECT_EQ(gl::parse_device_preference("software"), gl::DevicePreference::software);
  EXPECT_THROW(gl::parse_device_preference("gpu"), std::invalid_argument);
  EXPECT_THROW(HeadlessContext(gl::ContextOptions{3, 1}), std::invalid_argument);

  try {
    const HeadlessContext software(gl::ContextOptions{.prefer = gl::DevicePreference::software});
    EXPECT_TRUE(software.is_software()) << software.renderer();
  } catch (const std::runtime_error& e) {  // a GPU machine without Mesa's llvmpipe
    EXPECT_NE(std::string(e.what()).find("prefer=software"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("is not a software rasterizer"), std::string::npos) << e.what();
  }
  try {
    const HeadlessContext hardware(gl::ContextOptions{.prefer = gl::DevicePreference::hardware});
    EXPECT_FALSE(hardware.is_software()) << hardware.renderer();
  } catch (const std::runtime_error& e) {  // a machine without a GPU, like CI
    EXPECT_NE(std::string(e.what()).find("prefer=hardware"), std::string::npos) << e.what();
  }
}

TEST(HeadlessContext, UnavailableVersionThrowsNamingEglCalls) {
  try {
    const HeadlessContext context(gl::ContextOptions{.gl_major = 9, .gl_minor = 9});
    FAIL() << "a GL 9.9 context was created: " << context.version();
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("GL 9.9"), std::string::npos) << what;
    EXPECT_NE(what.find("eglCreateContext"), std::string::npos) << what;
    EXPECT_NE(what.find("0x"), std::string::npos) << what;  // the EGL error code
  }
}

TEST(HeadlessContext, DebugContextRoutesMessages) {
  const HeadlessContext context(gl::ContextOptions{.debug = true});
  EXPECT_TRUE(context.debug());
  glBindTexture(GL_TEXTURE_2D, 123456);  // an invalid name: GL_INVALID_OPERATION, logged through spdlog
  EXPECT_THROW(gl::check_gl_error("bind of an invalid texture"), std::runtime_error);
  gl::check_gl_error("after draining");
}

/// ZENITH_GL_DEBUG set for the test's length, restored after.
class GlDebugVariable {
 public:
  explicit GlDebugVariable(const char* value) {
    if (const char* old = std::getenv(kName)) previous_ = old;
    setenv(kName, value, 1);
  }
  ~GlDebugVariable() {
    if (previous_)
      setenv(kName, previous_->c_str(), 1);
    else
      unsetenv(kName);
  }
  GlDebugVariable(const GlDebugVariable&) = delete;
  GlDebugVariable& operator=(const GlDebugVariable&) = delete;

 private:
  static constexpr const char* kName = "ZENITH_GL_DEBUG";
  std::optional<std::string> previous_;
};

TEST(HeadlessContext, ZenithGlDebugMakesEveryContextADebugOneWithAsynchronousMessages) {
  {
    const GlDebugVariable on("1");
    const HeadlessContext context;
    EXPECT_TRUE(context.debug());
    EXPECT_TRUE(glIsEnabled(GL_DEBUG_OUTPUT));
    EXPECT_FALSE(glIsEnabled(GL_DEBUG_OUTPUT_SYNCHRONOUS)) << "a support log must not slow the frames";
    glBindTexture(GL_TEXTURE_2D, 123456);
    EXPECT_THROW(gl::check_gl_error("bind of an invalid texture"), std::runtime_error);
  }
  for (const char* off : {"0", ""}) {
    const GlDebugVariable value(off);
    const HeadlessContext context;
    EXPECT_FALSE(context.debug()) << "ZENITH_GL_DEBUG=\"" << off << "\"";
  }
}

TEST_F(GlTest, TestPatternComputeShaderMatchesCpp) {
  const ShaderProgram program = testing::load_test_compute_program("test_pattern.comp");
  EXPECT_EQ(program.work_group_size(), (std::array<int, 3>{4, 4, 2}));
  const int w = 8, h = 4, d = 3;  // d = 3 is not a multiple of the work group's 2: out-of-range invocations return
  expect_floats_near(run_pattern(program, w, h, d), expected_pattern(w, h, d), 1e-6f);
}

TEST_F(GlTest, DefineVariantsChangeTheOutput) {
  const std::vector<gl::ShaderDefine> no_index = {{"PATTERN_INDEX_TERM", "0"}, {"PATTERN_SCALE", "2.0"}};
  const ShaderProgram variant = testing::load_test_compute_program("test_pattern.comp", no_index);
  const std::vector<float> out = run_pattern(variant, 5, 3, 2);
  expect_floats_near(out, expected_pattern(5, 3, 2, 2.0f, false), 1e-6f);
  const ShaderProgram plain = testing::load_test_compute_program("test_pattern.comp");
  EXPECT_NE(out, run_pattern(plain, 5, 3, 2));
}

/// render/gl/program_binary_cache.h: a program stored after it links comes back
/// from the file in a later cache (a later run), computes the same, and a file
/// the driver refuses is removed and the program compiled again.
TEST_F(GlTest, ProgramBinaryCacheGivesBackTheSameProgramAndRecompilesARefusedOne) {
  std::string name = "zenith-program-binaries-";
  name += std::to_string(::getpid());
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / name;
  std::filesystem::remove_all(dir);
  const std::vector<float> expected = expected_pattern(5, 3, 2);
  {
    gl::ProgramBinaryCache cache(dir);
    if (!cache.enabled()) GTEST_SKIP() << "this driver offers no program binary format";
    const ShaderProgram p = render::compute_program(testing::load_test_shader("test_pattern.comp"), {}, &cache);
    expect_floats_near(run_pattern(p, 5, 3, 2), expected, 1e-6f);
    EXPECT_EQ(cache.statistics().stored, 1);
    EXPECT_EQ(cache.statistics().loaded, 0);
    // Another variant is another program, under another key.
    const std::vector<gl::ShaderDefine> scaled = {{"PATTERN_SCALE", "2.0"}};
    render::compute_program(testing::load_test_shader("test_pattern.comp"), scaled, &cache);
    EXPECT_EQ(cache.statistics().stored, 2);
  }
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(dir)) files.push_back(e.path());
  ASSERT_EQ(files.size(), 2u);
  {
    gl::ProgramBinaryCache cache(dir);  // a later run
    const ShaderProgram p = render::compute_program(testing::load_test_shader("test_pattern.comp"), {}, &cache);
    EXPECT_EQ(cache.statistics().loaded, 1);
    EXPECT_EQ(cache.statistics().stored, 0);
    EXPECT_EQ(p.work_group_size(), (std::array<int, 3>{4, 4, 2}));
    expect_floats_near(run_pattern(p, 5, 3, 2), expected, 1e-6f);
  }
  for (const auto& f : files) std::filesystem::resize_file(f, 20);  // as a driver update would leave them: unusable
  {
    gl::ProgramBinaryCache cache(dir);
    const ShaderProgram p = render::compute_program(testing::load_test_shader("test_pattern.comp"), {}, &cache);
    EXPECT_EQ(cache.statistics().loaded, 0);
    EXPECT_EQ(cache.statistics().refused, 1);
    EXPECT_EQ(cache.statistics().stored, 1);  // compiled and stored anew
    expect_floats_near(run_pattern(p, 5, 3, 2), expected, 1e-6f);
  }
  std::filesystem::remove_all(dir);
}

TEST_F(GlTest, SyntaxErrorThrowsWithShaderNameAndLine) {
  const gl::ShaderCode broken{"broken_test.comp",
                              "#version 450 core\n"
                              "layout(local_size_x = 1) in;\n"
                              "void main() {\n"
                              "  float x = 1.0 +;\n"
                              "}\n",
                              {}};
  try {
    ShaderProgram::compute(broken, std::vector<gl::ShaderDefine>{{"UNUSED", "1"}});
    FAIL() << "compiled";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("broken_test.comp"), std::string::npos) << what;
    EXPECT_NE(what.find("failed to compile"), std::string::npos) << what;
    // The driver's line number is the file's (the injected #define does not shift it),
    // and the offending line is quoted under it.
    EXPECT_NE(what.find("broken_test.comp:4 | float x = 1.0 +;"), std::string::npos) << what;
  }
}

TEST_F(GlTest, NvidiasLoopUnrollPragmaKeepsLineNumbersAndIsIgnoredElsewhere) {
  // The text ShaderProgram::compute compiles again when NVIDIA's compiler fails
  // on an unrolled loop (gl::kNvidiaLoopUnrollOff): the pragma after #version,
  // every later line at its own number.
  const std::string pragma[] = {std::string(gl::kNvidiaLoopUnrollOff)};
  EXPECT_EQ(gl::insert_after_version("s", "// header\n#version 450 core\nvoid main() {}\n", pragma),
            "// header\n#version 450 core\n#pragma optionNV(unroll none)\n#line 3 0\nvoid main() {}\n");
  EXPECT_THROW(gl::insert_after_version("s", "void main() {}\n", pragma), std::invalid_argument);
  EXPECT_TRUE(gl::is_nvidia_unroll_failure("0(46) : error C5025: lvalue in array access too complex"));
  EXPECT_FALSE(gl::is_nvidia_unroll_failure("0:4(17): error: syntax error, unexpected ';'"));

  // This driver compiles the pragma'd text (other compilers ignore the pragma)
  // and names a later error at the file's own line.
  const std::string source = "#version 450 core\nlayout(local_size_x = 1) in;\nvoid main() {\n  float x = 1.0 +;\n}\n";
  const gl::ShaderCode rolled{"rolled_test.comp", gl::insert_after_version("rolled_test.comp", source, pragma), {}};
  try {
    ShaderProgram::compute(rolled, std::vector<gl::ShaderDefine>{{"UNUSED", "1"}});
    FAIL() << "compiled";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("rolled_test.comp:4 | float x = 1.0 +;"), std::string::npos) << e.what();
  }
  const gl::ShaderCode fine{"unrolled_off.comp",
                            gl::insert_after_version("unrolled_off.comp",
                                                     "#version 450 core\nlayout(local_size_x = 1) in;\n"
                                                     "layout(std430, binding = 0) buffer B { float v[]; };\n"
                                                     "void main() { for (int i = 0; i < 8; ++i) v[i] = float(i); }\n",
                                                     pragma),
                            {}};
  EXPECT_NO_THROW(ShaderProgram::compute(fine));
}

/// main.comp, which includes lib/common.glsl, whose line 3 does not compile.
ExpandedShader main_with_an_error_in_its_include() {
  const std::map<std::string, std::string, std::less<>> files = {
      {"main.comp", "#version 450 core\nlayout(local_size_x = 1) in;\n#include \"lib/common.glsl\"\nvoid main() {}\n"},
      {"lib/common.glsl", "// common\nfloat f() { return 1.0; }\nfloat g() { return undefined_name; }\n"}};
  return expand_includes("main.comp", files.at("main.comp"), [&](std::string_view n) {
    auto it = files.find(n);
    return it == files.end() ? std::nullopt : std::optional<std::string_view>(it->second);
  });
}

TEST_F(GlTest, ErrorInAnIncludedFileNamesThatFileAndLine) {
  const ExpandedShader e = main_with_an_error_in_its_include();
  try {
    ShaderProgram::compute(gl::ShaderCode{e.name, e.text, e.files});
    FAIL() << "compiled";
  } catch (const std::runtime_error& ex) {
    const std::string what = ex.what();
    EXPECT_NE(what.find("lib/common.glsl:3 | float g() { return undefined_name; }"), std::string::npos) << what;
    EXPECT_NE(what.find("1 = lib/common.glsl"), std::string::npos) << what;
  }
}

/// The shared binding points (render/shader_bindings.h), then `extra`: what
/// render::compute_program defines before a shader's own.
std::vector<gl::ShaderDefine> interface_and(std::vector<gl::ShaderDefine> extra = {}) {
  std::vector<gl::ShaderDefine> all = shader_interface_defines();
  all.insert(all.end(), extra.begin(), extra.end());
  return all;
}

/// A starter of the test pattern scaled by `scale` that owns its code and its
/// scale, as ProgramBuilds::build_on needs.
gl::ProgramBuilds::Starter pattern_starter(const ExpandedShader& pattern, std::string scale) {
  return [code = gl::ShaderCode{pattern.name, pattern.text, pattern.files}, scale = std::move(scale)] {
    return gl::ShaderBuild::compute(code, interface_and({{"PATTERN_SCALE", scale}}));
  };
}

/// A starter that says when it is called (on the build thread, where that
/// thread begins the build) and, where asked, holds the build there until
/// the test lets it go: the tests below order the two threads by these
/// signals, never by sleeping, so a loaded machine cannot reorder them.
struct BuildSignals {
  std::atomic<bool> called{false};
  std::promise<void> begun;
  std::shared_future<void> begun_future = begun.get_future().share();
  std::promise<void> release;
  std::shared_future<void> release_future = release.get_future().share();

  gl::ProgramBuilds::Starter signalling(gl::ProgramBuilds::Starter starter, bool held) {
    return [this, starter = std::move(starter), held] {
      if (!called.exchange(true)) begun.set_value();
      // Bounded: a test that fails before letting it go does not hang the thread.
      if (held) release_future.wait_for(std::chrono::seconds(20));
      return starter();
    };
  }
  bool wait_begun() const { return begun_future.wait_for(std::chrono::seconds(20)) == std::future_status::ready; }
};

/// render/gl/shader_build.h: builds started together (on the driver's
/// threads where it has GL_KHR_parallel_shader_compile), finished later, in
/// any order; each is the program ShaderProgram::compute makes.
TEST_F(GlTest, ShaderBuildsStartedTogetherFinishInAnyOrder) {
  const ExpandedShader pattern = testing::load_test_shader("test_pattern.comp");
  const gl::ShaderCode code{pattern.name, pattern.text, pattern.files};
  const std::vector<gl::ShaderDefine> scaled = {{"PATTERN_SCALE", "2.0"}, {"PATTERN_INDEX_TERM", "0"}};
  gl::ShaderBuild plain = gl::ShaderBuild::compute(code, interface_and());
  gl::ShaderBuild variant = gl::ShaderBuild::compute(code, interface_and(scaled));
  EXPECT_TRUE(plain.started());
  EXPECT_EQ(plain.name(), "test_pattern.comp");
  // Polled as a renderer would between frames: a build completes on its own.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!variant.ready() && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  EXPECT_TRUE(variant.ready());
  const ShaderProgram second = variant.finish();  // the later one first
  const ShaderProgram first = plain.finish();
  EXPECT_FALSE(plain.started());
  EXPECT_THROW(plain.finish(), std::logic_error);  // once only
  EXPECT_EQ(first.work_group_size(), (std::array<int, 3>{4, 4, 2}));
  expect_floats_near(run_pattern(first, 5, 3, 2), expected_pattern(5, 3, 2), 1e-6f);
  expect_floats_near(run_pattern(second, 5, 3, 2), expected_pattern(5, 3, 2, 2.0f, false), 1e-6f);
  // A build never finished is abandoned without a trace (its GL objects deleted).
  { const gl::ShaderBuild abandoned = gl::ShaderBuild::compute(code, interface_and()); }
  gl::check_gl_error("after an abandoned build");
}

TEST_F(GlTest, AStartedBuildReportsItsCompileErrorAtFinishWithFileAndLine) {
  const ExpandedShader e = main_with_an_error_in_its_include();
  const ExpandedShader pattern = testing::load_test_shader("test_pattern.comp");
  gl::ShaderBuild broken = gl::ShaderBuild::compute(gl::ShaderCode{e.name, e.text, e.files});  // does not throw
  gl::ShaderBuild fine =
      gl::ShaderBuild::compute(gl::ShaderCode{pattern.name, pattern.text, pattern.files}, interface_and());
  try {
    broken.finish();
    FAIL() << "compiled";
  } catch (const gl::ShaderBuildError& ex) {
    const std::string what = ex.what();
    EXPECT_EQ(ex.program(), "main.comp");
    EXPECT_NE(what.find("shader 'main.comp' (compute) failed to compile"), std::string::npos) << what;
    EXPECT_NE(what.find("lib/common.glsl:3 | float g() { return undefined_name; }"), std::string::npos) << what;
  }
  // The other build, started beside the failing one, is unharmed.
  expect_floats_near(run_pattern(fine.finish(), 5, 3, 2), expected_pattern(5, 3, 2), 1e-6f);

  // A graphics pair: the failing stage's own name and line.
  const gl::ShaderCode vertex{"v.vert", "#version 450 core\nvoid main() { gl_Position = vec4(0); }\n", {}};
  const gl::ShaderCode fragment{"f.frag", "#version 450 core\nout vec4 c;\nvoid main() {\n  c = vec3(1);\n}\n", {}};
  gl::ShaderBuild pair = gl::ShaderBuild::graphics(vertex, fragment);
  try {
    pair.finish();
    FAIL() << "linked";
  } catch (const gl::ShaderBuildError& ex) {
    EXPECT_EQ(ex.program(), "v.vert + f.frag");
    EXPECT_NE(std::string(ex.what()).find("f.frag:4 | c = vec3(1);"), std::string::npos) << ex.what();
  }
}

/// NVIDIA's C5025 (a loop its compiler unrolled and could not index) is built
/// again with loop unrolling off (gl::kNvidiaLoopUnrollOff), from a started
/// build as from ShaderProgram::compute. ShaderFaults::fail_shader_c5025 makes any
/// driver fail that way while the pragma is absent (tests/render/shader_faults.h).
TEST_F(GlTest, TheC5025RetryBuildsAStartedProgramWithLoopUnrollingOff) {
  const ExpandedShader pattern = testing::load_test_shader("test_pattern.comp");
  const gl::ShaderCode code{pattern.name, pattern.text, pattern.files};
  std::optional<testing::ScopedShaderFaults> fail(std::in_place, testing::ShaderFaults::c5025_in("test_pattern.comp"));
  gl::ShaderBuild build = gl::ShaderBuild::compute(code, interface_and());
  gl::ShaderBuild other = gl::ShaderBuild::compute(code, interface_and({{"PATTERN_SCALE", "2.0"}}));
  const ShaderProgram retried = build.finish();
  expect_floats_near(run_pattern(retried, 5, 3, 2), expected_pattern(5, 3, 2), 1e-6f);
  expect_floats_near(run_pattern(other.finish(), 5, 3, 2), expected_pattern(5, 3, 2, 2.0f), 1e-6f);
  // The hook fails the first try for real: a graphics pair, which has no retry, shows its message.
  fail.reset();
  const testing::ScopedShaderFaults fail_vertex(testing::ShaderFaults::c5025_in("v.vert"));
  const gl::ShaderCode vertex{"v.vert", "#version 450 core\nvoid main() { gl_Position = vec4(0); }\n", {}};
  const gl::ShaderCode fragment{"f.frag", "#version 450 core\nout vec4 c;\nvoid main() { c = vec4(1); }\n", {}};
  try {
    gl::ShaderBuild::graphics(vertex, fragment).finish();
    FAIL() << "linked";
  } catch (const gl::ShaderBuildError& ex) {
    EXPECT_TRUE(gl::is_nvidia_unroll_failure(ex.what())) << ex.what();
  }
}

/// render/gl/program_builds.h: programs by key, started ahead (parallel) or
/// built where first asked for (serial); a failure is thrown where the program
/// is asked for and not kept.
TEST_F(GlTest, ProgramBuildsStartAheadOrOneAtATimeAndCountWhatTheyCost) {
  const ExpandedShader pattern = testing::load_test_shader("test_pattern.comp");
  const gl::ShaderCode code{pattern.name, pattern.text, pattern.files};
  auto starter = [&](std::string scale) {
    return [&code, scale] { return gl::ShaderBuild::compute(code, interface_and({{"PATTERN_SCALE", scale}})); };
  };
  const gl::ShaderCode broken{
      "broken_test.comp", "#version 450 core\nlayout(local_size_x = 1) in;\nvoid main() {\n  x;\n}\n", {}};
  const auto broken_starter = [&] { return gl::ShaderBuild::compute(broken); };
  for (const gl::CompileMode mode : {gl::CompileMode::parallel, gl::CompileMode::serial}) {
    SCOPED_TRACE(gl::to_string(mode));
    gl::ProgramBuilds builds(mode);
    builds.start("one", starter("1.0"));
    builds.start("two", starter("2.0"));
    builds.start("three", starter("3.0"));
    builds.start("broken", broken_starter);
    builds.start("one", starter("9.0"));  // already started: the first one stays
    const ShaderProgram& two = builds.get("two", starter("2.0"));
    EXPECT_EQ(&builds.get("two", starter("2.0")), &two) << "built once";
    expect_floats_near(run_pattern(two, 4, 2, 2), expected_pattern(4, 2, 2, 2.0f), 1e-6f);
    expect_floats_near(run_pattern(builds.get("one", starter("1.0")), 4, 2, 2), expected_pattern(4, 2, 2), 1e-6f);
    EXPECT_THROW(builds.get("broken", broken_starter), gl::ShaderBuildError);
    EXPECT_THROW(builds.get("broken", broken_starter), gl::ShaderBuildError) << "not kept: built again";
    expect_floats_near(run_pattern(builds.get("four", starter("4.0")), 4, 2, 2), expected_pattern(4, 2, 2, 4.0f),
                       1e-6f);
    const gl::ProgramBuilds::Statistics& s = builds.statistics();
    EXPECT_EQ(s.built, 3);  // one, two, four; three abandoned, broken failed
    EXPECT_EQ(s.most_in_flight, mode == gl::CompileMode::parallel ? 4 : 1);
    EXPECT_GT(s.start_s, 0.0);
    EXPECT_GT(s.seconds(), s.wait_s);
    EXPECT_NE(builds.summary().find("3 programs, "), std::string::npos) << builds.summary();
  }
  gl::check_gl_error("after the builds");
}

/// ProgramBuilds::build_on: builds started while a thread of a shared context
/// is set are compiled and linked there (llvmpipe compiles in the calling
/// thread), from starters that own their inputs, and give this context the
/// same programs, the same errors, and — where the thread goes before it
/// reached a build — a program built here instead.
TEST_F(GlTest, ProgramBuildsOnASecondThreadGiveTheSameProgramsAndErrors) {
  const ExpandedShader pattern = testing::load_test_shader("test_pattern.comp");
  const auto starter = [&](std::string scale) { return pattern_starter(pattern, std::move(scale)); };
  const gl::ShaderCode broken{
      "broken_test.comp", "#version 450 core\nlayout(local_size_x = 1) in;\nvoid main() {\n  x;\n}\n", {}};
  const auto broken_starter = [broken] { return gl::ShaderBuild::compute(broken); };
  std::string in_place_error;
  try {
    broken_starter().finish();
  } catch (const gl::ShaderBuildError& e) {
    in_place_error = e.what();
  }
  ASSERT_FALSE(in_place_error.empty());

  gl::ProgramBuilds builds(gl::CompileMode::parallel);
  {
    BuildSignals one;
    gl::FirstDispatchWarmup thread;
    builds.build_on(&thread);
    builds.start("one", one.signalling(starter("1.0"), false));
    builds.start("two", starter("2.0"));
    builds.start("broken", broken_starter);
    ASSERT_TRUE(one.wait_begun()) << "the thread began no build in 20 s";
    expect_floats_near(run_pattern(builds.get("two", {}), 4, 2, 2), expected_pattern(4, 2, 2, 2.0f), 1e-6f);
    expect_floats_near(run_pattern(builds.get("one", {}), 4, 2, 2), expected_pattern(4, 2, 2), 1e-6f);
    try {
      builds.get("broken", broken_starter);
      ADD_FAILURE() << "the broken shader built";
    } catch (const gl::ShaderBuildError& e) {
      EXPECT_EQ(std::string(e.what()), in_place_error) << "the same message as built here";
    }
    // A build the thread had not begun when asked for is taken back and built here (usually "two",
    // queued behind "one"); the others the thread built.
    EXPECT_EQ(builds.statistics().built_on_thread + builds.statistics().built_while_waiting, 2);
    EXPECT_GT(builds.statistics().built_on_thread, 0) << "\"one\", begun there before it was asked for";
    // The thread counts a build once it returns, after the program went back through its future: those
    // it built, and the broken one where it began it before it was asked for.
    for (int k = 0; k < 400 && !thread.idle(); ++k) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    EXPECT_GE(thread.statistics().built, builds.statistics().built_on_thread);
    EXPECT_LE(thread.statistics().built, builds.statistics().built_on_thread + 1);
    EXPECT_GT(thread.statistics().build_s, 0.0);
    EXPECT_NE(builds.summary().find(fmt::format("{} of them compiled on a second thread, one at a time, {} here while "
                                                "waiting for it",
                                                builds.statistics().built_on_thread,
                                                builds.statistics().built_while_waiting)),
              std::string::npos)
        << builds.summary();
    builds.build_on(nullptr);
  }
  {  // the thread held up by a slow build: the one queued behind it, asked for, is built here meanwhile
    BuildSignals slow;
    gl::FirstDispatchWarmup thread;
    builds.build_on(&thread);
    const int here_before = builds.statistics().built_while_waiting;
    builds.start("slow", slow.signalling(starter("9.0"), true));
    builds.start("queued", starter("10.0"));
    ASSERT_TRUE(slow.wait_begun()) << "the thread began no build in 20 s";
    expect_floats_near(run_pattern(builds.get("queued", {}), 4, 2, 2), expected_pattern(4, 2, 2, 10.0f), 1e-6f);
    EXPECT_EQ(builds.statistics().built_while_waiting, here_before + 1);
    slow.release.set_value();
    expect_floats_near(run_pattern(builds.get("slow", {}), 4, 2, 2), expected_pattern(4, 2, 2, 9.0f), 1e-6f);
    EXPECT_EQ(builds.statistics().built_while_waiting, here_before + 1) << "the slow one was begun there";
    builds.build_on(nullptr);
  }
  {  // six builds queued and the thread gone at once: it finishes the one in hand, drops the rest
    auto thread = std::make_unique<gl::FirstDispatchWarmup>();
    builds.build_on(thread.get());
    for (int k = 3; k <= 8; ++k) builds.start(fmt::format("scale {}", k), starter(fmt::format("{}.0", k)));
    thread.reset();
    builds.build_on(nullptr);
  }
  for (int k = 3; k <= 8; ++k)
    expect_floats_near(run_pattern(builds.get(fmt::format("scale {}", k), {}), 4, 2, 2),
                       expected_pattern(4, 2, 2, static_cast<float>(k)), 1e-6f);
  EXPECT_LT(builds.statistics().built_on_thread, 2 + 6) << "the dropped builds were built here";
  gl::check_gl_error("after the builds");
}

/// ProgramBuilds::build_on with several threads (CompileMode::contexts): each
/// build goes to the next thread in turn, so three builds on three threads run
/// one per thread, and each program is the one its starter asked for.
TEST_F(GlTest, ProgramBuildsOnSeveralThreadsTakeTurnsAndGiveTheSamePrograms) {
  const ExpandedShader pattern = testing::load_test_shader("test_pattern.comp");
  const auto starter = [&](std::string scale) { return pattern_starter(pattern, std::move(scale)); };
  gl::ProgramBuilds builds(gl::CompileMode::contexts);
  std::vector<std::unique_ptr<gl::FirstDispatchWarmup>> threads;
  for (int k = 0; k < 3; ++k) threads.push_back(std::make_unique<gl::FirstDispatchWarmup>());
  builds.build_on({threads[0].get(), threads[1].get(), threads[2].get()});
  for (int k = 1; k <= 3; ++k) builds.start(fmt::format("scale {}", k), starter(fmt::format("{}.0", k)));
  for (int k = 3; k >= 1; --k)
    expect_floats_near(run_pattern(builds.get(fmt::format("scale {}", k), {}), 4, 2, 2),
                       expected_pattern(4, 2, 2, static_cast<float>(k)), 1e-6f);
  EXPECT_EQ(builds.statistics().built_on_thread, 3);
  for (const auto& thread : threads) {
    for (int k = 0; k < 400 && !thread->idle(); ++k) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    EXPECT_EQ(thread->statistics().built, 1) << "one build per thread";
  }
  EXPECT_NE(builds.summary().find("3 of them compiled on 3 threads of their own"), std::string::npos)
      << builds.summary();
  EXPECT_STREQ(to_string(gl::CompileMode::contexts), "contexts");
  builds.build_on(nullptr);
  gl::check_gl_error("after the builds");
}

/// ProgramBuilds' builds for a later frame (BuildFor::a_later_frame): left
/// alone by warm_started, finished by finish_ahead once ready without
/// waiting (counted apart from the frames' builds), their first dispatch
/// warmed on the thread; a failing one is thrown once, where it is finished.
TEST_F(GlTest, ProgramBuildsForALaterFrameAreFinishedOnceReadyWithoutWaiting) {
  const ExpandedShader pattern = testing::load_test_shader("test_pattern.comp");
  const auto starter = [&](std::string scale) { return pattern_starter(pattern, std::move(scale)); };
  gl::ProgramBuilds builds(gl::CompileMode::parallel);
  gl::FirstDispatchWarmup thread;
  builds.build_on(&thread);
  builds.start("now", starter("1.0"));
  builds.start("later", starter("3.0"), gl::BuildFor::a_later_frame);
  builds.start("later too", starter("5.0"), gl::BuildFor::a_later_frame);
  builds.warm_started(thread, {}, [](const gl::ShaderProgram&) { return 0; });
  EXPECT_TRUE(builds.built("now")) << "this frame's build: finished by warm_started";
  EXPECT_FALSE(builds.built("later")) << "left for finish_ahead";
  bool finished = false;
  for (int k = 0; k < 400 && !finished; ++k) {  // the thread builds them meanwhile
    finished = builds.finish_ahead(&thread, {});
    if (!finished) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_TRUE(finished) << "not built within 4 s";
  EXPECT_TRUE(builds.built("later"));
  EXPECT_EQ(builds.statistics().built, 1) << "the frames' builds";
  EXPECT_EQ(builds.statistics().built_ahead, 2);
  EXPECT_EQ(builds.statistics().built_on_thread + builds.statistics().built_while_waiting, 1)
      << "\"now\": on the thread, or here where it had not begun it when warm_started asked";
  for (int k = 0; k < 400 && !thread.idle(); ++k) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  EXPECT_TRUE(thread.idle());
  EXPECT_GE(thread.statistics().warmed, 2) << "the later frame's programs warmed";
  expect_floats_near(run_pattern(builds.get("later", {}), 4, 2, 2), expected_pattern(4, 2, 2, 3.0f), 1e-6f);
  EXPECT_NE(builds.summary().find("2 more built ahead for later frames"), std::string::npos) << builds.summary();

  const gl::ShaderCode broken{
      "broken_test.comp", "#version 450 core\nlayout(local_size_x = 1) in;\nvoid main() {\n  x;\n}\n", {}};
  builds.start(
      "broken", [broken] { return gl::ShaderBuild::compute(broken); }, gl::BuildFor::a_later_frame);
  bool thrown = false;
  for (int k = 0; k < 400 && !thrown; ++k) {
    try {
      if (builds.finish_ahead(&thread, {})) break;
    } catch (const gl::ShaderBuildError&) {
      thrown = true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_TRUE(thrown);
  EXPECT_TRUE(builds.finish_ahead(&thread, {})) << "thrown once, then dropped";
  EXPECT_FALSE(builds.built("broken"));
  builds.build_on(nullptr);
  gl::check_gl_error("after the builds");
}

TEST_F(GlTest, TextureRoundTrips) {
  const std::vector<float> r = {1.5f, -2.0f, 3.25f, 1e-30f, 6.0f, 7.0f};  // 3x2
  const Texture t2 = Texture::create_2d(TextureFormat::r32f, 3, 2, r);
  EXPECT_FALSE(t2.is_3d());
  EXPECT_EQ(t2.read(), r);

  std::vector<float> rg(2 * 2 * 3 * 4);
  for (std::size_t i = 0; i < rg.size(); ++i) rg[i] = static_cast<float>(i) * 0.125f - 1.0f;
  Texture t3 = Texture::create_3d(TextureFormat::rg32f, 2, 3, 4, rg);
  EXPECT_EQ(t3.read(), rg);
  for (float& v : rg) v *= 2.0f;
  t3.upload(rg);
  EXPECT_EQ(t3.read(), rg);
  EXPECT_THROW(t3.upload(std::vector<float>(3)), std::invalid_argument);

  const Texture zero = Texture::create_3d(TextureFormat::rgba32f, 2, 2, 2);
  EXPECT_EQ(zero.read(), std::vector<float>(32, 0.0f));
  EXPECT_THROW(Texture::create_2d(TextureFormat::r32f, 0, 4), std::invalid_argument);
  EXPECT_THROW(Texture::create_3d(TextureFormat::r32f, 1 << 20, 1 << 20, 1 << 20), std::runtime_error);
}

TEST_F(GlTest, StorageBufferThroughACompute) {
  const gl::ShaderCode doubler{"doubler.comp",
                               "#version 450 core\n"
                               "layout(local_size_x = 64) in;\n"
                               "layout(std430, binding = 0) buffer Data { float values[]; };\n"
                               "layout(std140, binding = 1) uniform Params { float factor; };\n"
                               "uniform uint count;\n"
                               "void main() {\n"
                               "  uint i = gl_GlobalInvocationID.x;\n"
                               "  if (i < count) values[i] *= factor;\n"
                               "}\n",
                               {}};
  const ShaderProgram program = ShaderProgram::compute(doubler);
  std::vector<float> values(100);
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = static_cast<float>(i);
  const gl::Buffer data = gl::Buffer::from(std::span<const float>(values));
  const float params[4] = {3.0f, 0, 0, 0};
  const gl::Buffer uniforms = gl::Buffer::from(std::span<const float>(params));
  data.bind_storage(0);
  uniforms.bind_uniform(1);
  EXPECT_TRUE(program.set_uniform("count", 100u));
  EXPECT_FALSE(program.set_uniform("not_there", 1));
  program.dispatch_covering(100);
  const std::vector<float> out = data.read<float>();
  ASSERT_EQ(out.size(), 100u);
  for (std::size_t i = 0; i < out.size(); ++i) EXPECT_EQ(out[i], 3.0f * static_cast<float>(i));
  EXPECT_THROW(gl::Buffer(0), std::invalid_argument);
  gl::Buffer zeros(16);
  EXPECT_EQ(zeros.read<std::uint32_t>(), std::vector<std::uint32_t>(4, 0u));
  EXPECT_THROW(zeros.upload(std::span<const float>(params), 4), std::out_of_range);
}

TEST_F(GlTest, AFenceSignalsOnceTheCommandsBeforeItAreDoneAndIsEmptyAfterAWait) {
  gl::Fence none;
  EXPECT_TRUE(none.empty());
  EXPECT_TRUE(none.signalled());
  none.wait("nothing");  // returns at once
  gl::Fence fence = gl::Fence::after_issued_commands();
  EXPECT_FALSE(fence.empty());
  glFinish();
  EXPECT_TRUE(fence.signalled());
  gl::Fence moved = std::move(fence);
  EXPECT_TRUE(fence.empty());  // NOLINT(bugprone-use-after-move): a moved-from fence is empty
  EXPECT_FALSE(moved.empty());
  moved.wait("the test's commands");
  EXPECT_TRUE(moved.empty());
}

/// Sums the uints bound at binding 0 (`count` of them) into sums[slot] at binding 1.
ShaderProgram summing_program() {
  return ShaderProgram::compute({"sum.comp",
                                 "#version 450 core\n"
                                 "layout(local_size_x = 1) in;\n"
                                 "layout(std430, binding = 0) readonly buffer In { uint values[]; };\n"
                                 "layout(std430, binding = 1) buffer Out { uint sums[]; };\n"
                                 "uniform uint count, slot;\n"
                                 "void main() {\n"
                                 "  uint s = 0u;\n"
                                 "  for (uint i = 0u; i < count; ++i) s += values[i];\n"
                                 "  sums[slot] = s;\n"
                                 "}\n",
                                 {}});
}

TEST_F(GlTest, UploadStreamGivesEveryUploadOfAFrameBytesOfItsOwn) {
  // A band's lists are uploaded while the commands of the bands before, which
  // read other lists, may not have run: each upload must land where no
  // earlier one lies, and a shader bound to its range reads it from its first
  // element. Five uploads and five dispatches with no wait between them.
  const ShaderProgram sum = summing_program();
  gl::UploadStream stream(4096);
  gl::Buffer sums(8 * sizeof(std::uint32_t));
  sums.bind_storage(1);
  std::vector<gl::UploadRange> ranges;
  std::uint32_t expected[5] = {};
  for (std::uint32_t k = 0; k < 5; ++k) {
    // 700 uints (2 800 bytes) from the third upload on: no two of them fit one 4 096-byte chunk.
    std::vector<std::uint32_t> values(k < 2 ? 10 + k : 700);
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = 1000 * (k + 1) + static_cast<std::uint32_t>(i);
    for (std::uint32_t v : values) expected[k] += v;
    ranges.push_back(stream.upload(std::span<const std::uint32_t>(values)));
    ranges.back().bind_storage(0);
    sum.set_uniform("count", static_cast<unsigned>(values.size()));
    sum.set_uniform("slot", k);
    sum.dispatch(1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  }
  const std::vector<std::uint32_t> out = sums.read<std::uint32_t>();
  for (std::uint32_t k = 0; k < 5; ++k) EXPECT_EQ(out[k], expected[k]) << "upload " << k;
  GLint alignment = 0;
  glGetIntegerv(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT, &alignment);
  for (std::size_t a = 0; a < ranges.size(); ++a) {
    EXPECT_EQ(ranges[a].offset_bytes % static_cast<std::size_t>(std::max(alignment, 16)), 0u) << "upload " << a;
    for (std::size_t b = 0; b < a; ++b)
      EXPECT_TRUE(ranges[a].buffer != ranges[b].buffer ||
                  ranges[a].offset_bytes >= ranges[b].offset_bytes + ranges[b].size_bytes ||
                  ranges[b].offset_bytes >= ranges[a].offset_bytes + ranges[a].size_bytes)
          << "uploads " << b << " and " << a << " overlap";
  }
  EXPECT_GE(stream.chunks(), 2u) << "2 800-byte uploads do not all fit one 4 096-byte chunk";
  // Nothing to upload still gives a range a storage binding takes (a positive size).
  const gl::UploadRange empty = stream.upload(std::span<const std::uint32_t>());
  EXPECT_GT(empty.size_bytes, 0u);
  empty.bind_storage(0);
  gl::check_gl_error("binding an empty upload");
  // An upload larger than a chunk gets a chunk of its size.
  const std::vector<std::uint32_t> large(3000, 1u);
  const gl::UploadRange big = stream.upload(std::span<const std::uint32_t>(large));
  big.bind_storage(0);
  sum.set_uniform("count", 3000u);
  sum.set_uniform("slot", 5u);
  sum.dispatch(1);
  EXPECT_EQ(sums.read<std::uint32_t>()[5], 3000u);
  EXPECT_THROW(gl::UploadStream(0), std::invalid_argument);
}

TEST_F(GlTest, UploadStreamReusesAFramesBytesOnceTheGpuHasRunItsCommands) {
  // Frame after frame, each finished before the next: the first chunk is free
  // again every time (its fence signalled), so the stream holds one chunk.
  const ShaderProgram sum = summing_program();
  gl::UploadStream stream(4096);
  gl::Buffer sums(4 * sizeof(std::uint32_t));
  sums.bind_storage(1);
  for (std::uint32_t frame = 0; frame < 40; ++frame) {
    const std::vector<std::uint32_t> values(100, frame);
    const gl::UploadRange r = stream.upload(std::span<const std::uint32_t>(values));
    r.bind_storage(0);
    sum.set_uniform("count", 100u);
    sum.set_uniform("slot", 0u);
    sum.dispatch(1);
    stream.end_frame();
    glFinish();
    ASSERT_EQ(sums.read<std::uint32_t>()[0], 100 * frame) << "frame " << frame;
  }
  EXPECT_EQ(stream.chunks(), 1u);
  // Frames that never wait for the GPU: new chunks only while the fences
  // before have not signalled, never more than the bound.
  for (std::uint32_t frame = 0; frame < 200; ++frame) {
    const std::vector<std::uint32_t> values(900, frame);  // 3 600 bytes: a chunk a frame
    stream.upload(std::span<const std::uint32_t>(values)).bind_storage(0);
    sum.set_uniform("count", 900u);
    sum.dispatch(1);
    stream.end_frame();
  }
  EXPECT_LE(stream.chunks(), gl::UploadStream::kMaxChunks);
}

TEST_F(GlTest, UploadStreamNeverRefillsAChunkWhoseFrameTheGpuIsStillRunning) {
  // A frame whose dispatch runs long (10⁸ steps, each needing the one before), its
  // fence laid, then the next frame's upload at once: the first chunk is not
  // free yet, so the upload takes a second chunk instead of rewriting it.
  const ShaderProgram slow =
      ShaderProgram::compute({"slow.comp",
                              "#version 450 core\n"
                              "layout(local_size_x = 1) in;\n"
                              "layout(std430, binding = 0) readonly buffer In { uint values[]; };\n"
                              "layout(std430, binding = 1) buffer Out { uint sums[]; };\n"
                              "uniform uint steps;\n"
                              "void main() {\n"
                              "  uint s = 0u;\n"
                              "  for (uint i = 0u; i < steps; ++i) s = s * 1664525u + 1013904223u + values[s >> 30];\n"
                              "  sums[0] = s;\n"
                              "}\n",
                              {}});
  gl::UploadStream stream(4096);
  gl::Buffer sums(4 * sizeof(std::uint32_t));
  sums.bind_storage(1);
  const std::vector<std::uint32_t> first = {1, 2, 3, 4}, second = {5, 6, 7, 8};
  const gl::UploadRange a = stream.upload(std::span<const std::uint32_t>(first));
  a.bind_storage(0);
  ASSERT_TRUE(slow.set_uniform("steps", 100000000u));
  glFlush();
  const auto start = std::chrono::steady_clock::now();
  slow.dispatch(1);
  stream.end_frame();
  const gl::UploadRange b = stream.upload(std::span<const std::uint32_t>(second));
  const double issued_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  glFinish();
  const double ran_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("the slow dispatch: issued in %.3f s, ran in %.3f s\n", issued_s, ran_s);
  if (ran_s < 2.0 * issued_s) GTEST_SKIP() << "this driver ran the dispatch before returning from it";
  EXPECT_NE(b.buffer, a.buffer) << "the upload rewrote the chunk the running dispatch reads";
  EXPECT_EQ(stream.chunks(), 2u);
}

// --- GL-free: embedded shaders, includes, define injection --------------------

TEST(ShaderSource, EmbeddedShadersAreThere) {
  EXPECT_NE(testing::test_shader_source("test_pattern.comp").find("#include \"test_common.glsl\""),
            std::string_view::npos);
  const auto names = testing::test_shader_names();
  EXPECT_NE(std::find(names.begin(), names.end(), "test_common.glsl"), names.end());
  // The tests' programs are the test library's (tests/shaders/), not the production library's.
  const auto production = shader_names();
  EXPECT_NE(std::find(production.begin(), production.end(), "atmosphere_common.glsl"), production.end());
  for (const std::string& name : production) EXPECT_FALSE(name.starts_with("test_")) << name;
  try {
    (void)shader_source("nope.comp");
    FAIL();
  } catch (const std::out_of_range& e) {
    EXPECT_NE(std::string(e.what()).find("nope.comp"), std::string::npos);
  }
  const ExpandedShader e = testing::load_test_shader("test_pattern.comp");
  EXPECT_EQ(e.files, (std::vector<std::string>{"test_pattern.comp", "test_common.glsl"}));
  EXPECT_NE(e.text.find("vec4 test_pattern("), std::string::npos);
  EXPECT_EQ(e.text.find("#include"), std::string::npos);
}

TEST(ShaderSource, IncludesExpandOnceWithLineDirectives) {
  const std::map<std::string, std::string, std::less<>> files = {
      {"a/b.glsl", "#include \"c.glsl\"\nB\n"},  // c.glsl resolves to a/c.glsl first
      {"a/c.glsl", "C"},                         // no final newline
      {"c.glsl", "root C\n"},
      {"d.glsl", "#include \"a/c.glsl\" // again: expands to nothing\nD\n"}};
  auto resolve = [&](std::string_view n) {
    auto it = files.find(n);
    return it == files.end() ? std::nullopt : std::optional<std::string_view>(it->second);
  };
  const ExpandedShader e =
      expand_includes("main.comp", "#version 450\n#include \"a/b.glsl\"\n  #  include \"d.glsl\"\nM\n", resolve);
  EXPECT_EQ(e.text,
            "#version 450\n"
            "#line 1 1\n"
            "#line 1 2\n"
            "C\n"
            "#line 2 1\n"
            "B\n"
            "#line 3 0\n"
            "#line 1 3\n"
            "\n"
            "D\n"
            "#line 4 0\n"
            "M\n");
  EXPECT_EQ(e.files, (std::vector<std::string>{"main.comp", "a/b.glsl", "a/c.glsl", "d.glsl"}));
}

TEST(ShaderSource, IncludeErrorsNameFileAndLine) {
  const std::map<std::string, std::string, std::less<>> files = {
      {"x.glsl", "#include \"y.glsl\"\n"}, {"y.glsl", "\n#include \"x.glsl\"\n"}, {"v.glsl", "#version 450\n"}};
  auto resolve = [&](std::string_view n) {
    auto it = files.find(n);
    return it == files.end() ? std::nullopt : std::optional<std::string_view>(it->second);
  };
  auto message = [&](std::string_view source) {
    try {
      expand_includes("m.comp", source, resolve);
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message("\n#include \"missing.glsl\"\n"), "m.comp:2: #include \"missing.glsl\": no such shader file");
  EXPECT_EQ(message("#include \"x.glsl\"\n"), "y.glsl:2: #include cycle: m.comp -> x.glsl -> y.glsl -> x.glsl");
  EXPECT_EQ(message("#include \"v.glsl\"\n"), "v.glsl:1: #version in an included file");
  EXPECT_NE(message("#include <x.glsl>\n").find("malformed #include"), std::string::npos);
  EXPECT_NE(message("#include \"x.glsl\" junk\n").find("unexpected text"), std::string::npos);
}

TEST(ShaderSource, DefinesGoRightAfterVersion) {
  const std::vector<gl::ShaderDefine> defines = {{"USE_OZONE", "1"}, {"FLAG", ""}};
  EXPECT_EQ(gl::inject_defines("s", "// header\n#version 450 core\nvoid main() {}\n", defines),
            "// header\n#version 450 core\n#define USE_OZONE 1\n#define FLAG \n#line 3 0\nvoid main() {}\n");
  EXPECT_EQ(gl::inject_defines("s", "#version 450\nx\n", {}), "#version 450\nx\n");
  EXPECT_THROW(gl::inject_defines("s", "void main() {}\n", defines), std::invalid_argument);
  for (const char* bad : {"1X", "GL_FOO", "A__B", "A-B", ""})
    EXPECT_THROW(gl::inject_defines("s", "#version 450\n", std::vector<gl::ShaderDefine>{{bad, "1"}}),
                 std::invalid_argument)
        << bad;
  EXPECT_THROW(gl::inject_defines("s", "#version 450\n", std::vector<gl::ShaderDefine>{{"A", "1\n2"}}),
               std::invalid_argument);
}

}  // namespace
}  // namespace zenith::render
