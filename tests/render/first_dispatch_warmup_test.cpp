// render/gl/first_dispatch_warmup.h: a program dispatched once on the warm-up
// thread with stand-ins of the renderer's shapes leaves its machine code in
// Mesa's shader cache, where the renderer's own first dispatch finds it — and
// with stand-ins of another shape it does not (what the shapes are for).
#include "render/gl/first_dispatch_warmup.h"

#include <epoxy/gl.h>
#include <gtest/gtest.h>
#include <pthread.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "render/display/display_encoder.h"
#include "render/gl/egl_context.h"
#include "render/gl/shader_cache_writes.h"
#include "render/gl/shader_program.h"
#include "render/gl/texture.h"
#include "render/shader_bindings.h"

namespace zenith::render::gl {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

/// Samples a 3D table into a 2D half-float image, times `scale`.
ShaderProgram sampling_program(const std::string& variant) {
  const ShaderCode code{"warmup_test.comp",
                        "#version 450 core\n"
                        "layout(local_size_x = 4, local_size_y = 4) in;\n"
                        "layout(binding = 1) uniform sampler3D table;\n"
                        "layout(binding = 0, rgba16f) uniform writeonly image2D target;\n"
                        "uniform float scale;\n"
                        "void main() {\n"
                        "  const ivec2 p = ivec2(gl_GlobalInvocationID.xy);\n"
                        "  if (any(greaterThanEqual(p, imageSize(target)))) return;\n"
                        "  const vec3 uvw = vec3((vec2(p) + 0.5) / vec2(imageSize(target)), 0.5);\n"
                        "  imageStore(target, p, texture(table, uvw) * scale * VARIANT);\n"
                        "}\n",
                        {}};
  return ShaderProgram::compute(code, std::vector<ShaderDefine>{{"VARIANT", variant}});
}

std::size_t files_under(const fs::path& dir) {
  std::size_t n = 0;
  std::error_code error;
  for (fs::recursive_directory_iterator it(dir, error), end; !error && it != end; it.increment(error))
    if (it->is_regular_file()) ++n;
  return n;
}

/// The files under `dir` once Mesa has written what it had queued: the count
/// unchanged for half a second (its cache writes go through a queue thread
/// of its own), at most 10 s.
std::size_t settled_files_under(const fs::path& dir) {
  std::size_t count = files_under(dir);
  auto quiet_since = std::chrono::steady_clock::now();
  const auto until = quiet_since + 10s;
  while (std::chrono::steady_clock::now() < until) {
    std::this_thread::sleep_for(20ms);
    const std::size_t now = files_under(dir);
    if (now != count) {
      count = now;
      quiet_since = std::chrono::steady_clock::now();
    } else if (std::chrono::steady_clock::now() - quiet_since >= 500ms) {
      break;
    }
  }
  return count;
}

/// Waits, at most `limit`, until `done` holds.
template <typename Done>
bool wait_for(Done done, std::chrono::milliseconds limit) {
  const auto until = std::chrono::steady_clock::now() + limit;
  while (!done()) {
    if (std::chrono::steady_clock::now() > until) return false;
    std::this_thread::sleep_for(5ms);
  }
  return true;
}

/// A context whose Mesa shader cache is a fresh folder of the test's own.
class FirstDispatchWarmupTest : public ::testing::Test {
 protected:
  void SetUp() override {
    cache_ = fs::temp_directory_path() / ("zenith-warmup-mesa-cache-" + std::to_string(::getpid()));
    fs::remove_all(cache_);
    fs::create_directories(cache_);
    ::setenv("MESA_SHADER_CACHE_DIR", cache_.c_str(), 1);
    context_.emplace();
    if (!first_dispatch_warmup_worthwhile())
      GTEST_SKIP() << "not llvmpipe with its shader cache on (" << context_->renderer() << ")";
  }
  void TearDown() override {
    context_.reset();
    fs::remove_all(cache_);
  }

  fs::path cache_;
  std::optional<HeadlessContext> context_;
};

TEST_F(FirstDispatchWarmupTest, AWarmedProgramsFirstDispatchLoadsItsCodeFromMesasCache) {
  std::vector<float> texels(4 * 4 * 4 * 4);
  for (std::size_t i = 0; i < texels.size(); ++i) texels[i] = static_cast<float>(i % 4 + 1);  // (1, 2, 3, 4)
  const Texture table = Texture::create_3d(TextureFormat::rgba32f, 4, 4, 4, texels);
  const Texture target = Texture::create_2d(TextureFormat::rgba16f, 3, 5);  // not a power of two
  DispatchShapes shapes;
  shapes.sampled[{1, TextureShape::Kind::texture_3d}] = table.shape();
  shapes.images[{0, TextureShape::Kind::texture_2d}] = target.shape();
  DispatchShapes other_shapes = shapes;  // the same image, but 4 × 4: other machine code
  other_shapes.images[{0, TextureShape::Kind::texture_2d}].width = 4;
  other_shapes.images[{0, TextureShape::Kind::texture_2d}].height = 4;

  ShaderProgram warmed = sampling_program("1.0");
  ShaderProgram warmed_otherwise = sampling_program("2.0");
  FirstDispatchWarmup warmup;
  warmup.warm(warmed, shapes);
  warmup.warm(warmed_otherwise, other_shapes);
  ASSERT_TRUE(wait_for([&] { return warmup.statistics().warmed == 2; }, 60s)) << "the warm-up thread never ran";
  if (!wait_for([&] { return files_under(cache_) >= 2; }, 5s))
    GTEST_SKIP() << "Mesa's shader cache was opened before this test set its folder; run it alone, as ctest does";
  const std::size_t after_warmup = settled_files_under(cache_);

  // The renderer's side: the real texture and image, the program's first dispatch.
  const auto run = [&](const ShaderProgram& program, float scale) {
    table.bind(1);
    target.bind_image(0, ImageAccess::write_only);
    program.set_uniform("scale", scale);
    program.dispatch_covering(3, 5);
    return target.read();
  };
  const std::vector<float> out = run(warmed, 0.5f);
  for (std::size_t i = 0; i < out.size(); ++i) ASSERT_EQ(out[i], 0.5f * static_cast<float>(i % 4 + 1)) << "value " << i;
  EXPECT_EQ(settled_files_under(cache_), after_warmup) << "the warmed program's code was generated again";

  const std::vector<float> other = run(warmed_otherwise, 0.5f);
  EXPECT_EQ(other[4], 2.0f * 0.5f * 1.0f);
  EXPECT_TRUE(wait_for([&] { return files_under(cache_) > after_warmup; }, 5s))
      << "stand-ins of another shape made the same code: the test could not tell a miss";

  const FirstDispatchWarmup::Statistics s = warmup.statistics();
  EXPECT_EQ(s.queued, 2);
  EXPECT_EQ(s.warmed, 2);
  EXPECT_EQ(s.taken_back, 0);
  EXPECT_GT(s.warm_s, 0.0);
}

TEST_F(FirstDispatchWarmupTest, EveryProgramIsDispatchedRightWhoeverGetsToItFirst) {
  std::vector<float> texels(2 * 2 * 2 * 4, 1.0f);
  const Texture table = Texture::create_3d(TextureFormat::rgba32f, 2, 2, 2, texels);
  const Texture target = Texture::create_2d(TextureFormat::rgba16f, 3, 5);
  DispatchShapes shapes;
  shapes.sampled[{1, TextureShape::Kind::texture_3d}] = table.shape();
  shapes.images[{0, TextureShape::Kind::texture_2d}] = target.shape();
  std::vector<ShaderProgram> programs;
  for (int k = 1; k <= 6; ++k) programs.push_back(sampling_program(std::to_string(k) + ".0"));
  {
    FirstDispatchWarmup warmup;
    for (ShaderProgram& p : programs) warmup.warm(p, shapes);
    // The renderer's thread from the other end: it takes back what the warm-up
    // has not reached, waits for what it has in hand, and gets the right values either way.
    for (int k = 6; k >= 1; --k) {
      const ShaderProgram& p = programs[static_cast<std::size_t>(k - 1)];
      table.bind(1);
      target.bind_image(0, ImageAccess::write_only);
      p.set_uniform("scale", 0.25f);
      p.dispatch_covering(3, 5);
      const std::vector<float> out = target.read();
      EXPECT_EQ(out[0], 0.25f * static_cast<float>(k)) << "program " << k;
      EXPECT_TRUE(p.dispatched());
    }
    ASSERT_TRUE(wait_for([&] { return warmup.statistics().warmed + warmup.statistics().taken_back == 6; }, 60s));
    const FirstDispatchWarmup::Statistics s = warmup.statistics();
    EXPECT_EQ(s.queued, 6);
    EXPECT_GE(s.warmed, 1) << "the thread takes the first at once";
    EXPECT_LE(s.waited, s.warmed);
  }
  // The hooks outlive the warm-up: a program dispatched after it is gone runs as any other.
  ShaderProgram late = sampling_program("7.0");
  {
    FirstDispatchWarmup warmup;
    warmup.warm(late, shapes);
  }
  table.bind(1);
  target.bind_image(0, ImageAccess::write_only);
  late.set_uniform("scale", 1.0f);
  late.dispatch_covering(3, 5);
  EXPECT_EQ(target.read()[0], 7.0f);
}

/// A frame's radiance of 48 × 30 pixels (not powers of two), and a blend mask of its size.
struct DisplayFrame {
  static constexpr int kWidth = 48, kHeight = 30;
  Texture radiance = Texture::create_2d(TextureFormat::rgba32f, kWidth, kHeight,
                                        std::vector<float>(std::size_t{kWidth} * kHeight * 4, 0.5f));
  Texture mask = Texture::create_2d(TextureFormat::r32f, kWidth, kHeight,
                                    std::vector<float>(std::size_t{kWidth} * kHeight, 0.25f));
  display::OutputStage blended() const {
    display::OutputStage stage;
    stage.blended = true;
    stage.blend_mask = &mask;
    return stage;
  }
};

TEST_F(FirstDispatchWarmupTest, AWarmedDrawLeavesTheDisplayPassCodeInMesasCache) {
  const DisplayFrame frame;
  Texture display8 = Texture::create_2d(TextureFormat::rgba8, DisplayFrame::kWidth, DisplayFrame::kHeight);
  Texture display16 = Texture::create_2d(TextureFormat::rgba16, DisplayFrame::kWidth, DisplayFrame::kHeight);
  display::DisplayEncoder encoder;
  FirstDispatchWarmup warmup;
  encoder.warm_encode(warmup, frame.radiance, frame.blended(), display8);
  encoder.warm_encode(warmup, frame.radiance, frame.blended(), display8);  // queued once
  ASSERT_TRUE(wait_for([&] { return warmup.statistics().warmed >= 1; }, 60s)) << "the warm-up thread never drew";
  if (!wait_for([&] { return files_under(cache_) >= 1; }, 5s))
    GTEST_SKIP() << "Mesa's shader cache was opened before this test set its folder; run it alone, as ctest does";
  const std::size_t after_warmup = settled_files_under(cache_);

  encoder.encode(frame.radiance, frame.blended(), display8);
  // 0.5 tone mapped (1 − e^−0.5), times α = 0.25, sRGB-encoded, in codes.
  const double linear = (1.0 - std::exp(-0.5)) * 0.25;
  const double code = std::round(255.0 * (1.055 * std::pow(linear, 1.0 / 2.4) - 0.055));
  EXPECT_NEAR(display8.read()[0] * 255.0, code, 1.0);
  EXPECT_EQ(settled_files_under(cache_), after_warmup) << "the warmed display pass's code was generated again";
  EXPECT_EQ(warmup.statistics().queued, 1);

  encoder.encode(frame.radiance, frame.blended(), display16);  // not warmed: a 16-bit target is other code
  EXPECT_TRUE(wait_for([&] { return files_under(cache_) > after_warmup; }, 5s))
      << "a target of another format made the same code: the test could not tell a miss";
}

TEST_F(FirstDispatchWarmupTest, TheDisplayPassCodeDoesNotDependOnWhatOtherPassesLeftBound) {
  const DisplayFrame frame;
  Texture display = Texture::create_2d(TextureFormat::rgba8, DisplayFrame::kWidth, DisplayFrame::kHeight);
  const display::OutputStage unblended;  // no mask: its sampler reads nothing
  display::DisplayEncoder first;
  first.encode(frame.radiance, unblended, display);
  const std::vector<float> codes = display.read();
  if (!wait_for([&] { return files_under(cache_) >= 1; }, 5s))
    GTEST_SKIP() << "Mesa's shader cache was opened before this test set its folder; run it alone, as ctest does";
  const std::size_t after_first = settled_files_under(cache_);

  // Another pass leaves a texture of another format and shape on the blend mask's unit.
  const Texture stray = Texture::create_2d(TextureFormat::rg32f, 3, 5);
  stray.bind(binding::kBlendMaskUnit);
  display::DisplayEncoder second;  // a program of its own, the same code
  second.encode(frame.radiance, unblended, display);
  EXPECT_EQ(display.read(), codes);
  EXPECT_EQ(settled_files_under(cache_), after_first)
      << "the display pass compiled again for what another pass left bound (warm-ups could not match it)";
}

TEST(ShaderCacheWrites, AWriterRunningMeansNotDoneAndOneAsleepMeansDone) {
  // A thread named as Mesa's shader-cache writers are: busy (a write in hand),
  // the writes are not done; waiting for work, they are. Mesa's own writers
  // in this process may be busy for a moment: the "done" side is polled.
  std::mutex mutex;
  std::condition_variable wake;
  std::atomic<bool> named = false, spin = true;
  bool stop = false;
  std::thread writer([&] {
    pthread_setname_np(pthread_self(), "test:disk$7");
    named = true;
    while (spin) {
    }
    std::unique_lock lock(mutex);
    wake.wait(lock, [&] { return stop; });
  });
  for (int i = 0; i < 2000 && !named; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  ASSERT_TRUE(named);
  EXPECT_FALSE(shader_cache_writes_done()) << "a writer running";
  spin = false;
  bool done = false;
  for (int i = 0; i < 2000 && !done; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    done = shader_cache_writes_done();
  }
  EXPECT_TRUE(done) << "the writer asleep, waiting for work";
  {
    std::lock_guard lock(mutex);
    stop = true;
  }
  wake.notify_one();
  writer.join();
}

TEST(TextureShape, SaysWhatADriversCodeDependsOn) {
  const HeadlessContext context;
  const Texture plain = Texture::create_2d(TextureFormat::rgba32f, 256, 64);
  EXPECT_EQ(plain.shape(),
            (TextureShape{TextureShape::Kind::texture_2d, TextureFormat::rgba32f, 256, 64, 1, false, false}));
  const Texture volume = Texture::create_3d(TextureFormat::rg32f, 8, 3, 5);
  EXPECT_EQ(volume.shape(),
            (TextureShape{TextureShape::Kind::texture_3d, TextureFormat::rg32f, 8, 3, 5, false, false}));
  Texture maps =
      Texture::create_2d_array_mipmapped(TextureFormat::rgba16f, 8, 4, 3, std::vector<float>(8 * 4 * 3 * 4, 0.5f));
  maps.set_repeat_s(true);
  EXPECT_EQ(maps.shape(),
            (TextureShape{TextureShape::Kind::texture_2d_array, TextureFormat::rgba16f, 8, 4, 3, true, true}));
  const Texture moved = std::move(maps);
  EXPECT_TRUE(moved.shape().repeat_s) << "a move keeps the wrap";
}

}  // namespace
}  // namespace zenith::render::gl
