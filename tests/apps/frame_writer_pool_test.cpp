// The ordered writing stage of the offline pipeline (offline/frame_writer_pool.h): files written by
// several threads appear frame by frame in order, and an error keeps exactly the frames before it.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <future>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>

#include <unistd.h>

#include "core/sha256.h"
#include "offline/frame_writer_pool.h"

namespace zenith::app::offline {
namespace {

namespace fs = std::filesystem;

class WriterPoolTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::ostringstream name;
    name << "zenith-pool-" << ::getpid() << '-' << ::testing::UnitTest::GetInstance()->current_test_info()->name();
    dir_ = fs::temp_directory_path() / name.str();
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

/// "frame F file K" (a stream: GCC 12's -O3 warns falsely inside chained string additions).
std::string text_of(std::uint64_t f, std::size_t k) {
  std::ostringstream s;
  s << "frame " << f << " file " << k;
  return s.str();
}

/// "fF-K.txt".
std::string name_of(std::uint64_t f, std::size_t k) {
  std::ostringstream s;
  s << 'f' << f << '-' << k << ".txt";
  return s.str();
}

void write_text(const fs::path& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

/// Frame `f` with two files, their text "frame f file k"; `before` runs in the writing thread first.
FrameWriterPool::Frame frame_of(const fs::path& dir, std::uint64_t f, std::function<void(std::size_t)> before,
                                std::atomic<int>& released) {
  FrameWriterPool::Frame frame;
  frame.frame = f;
  for (std::size_t k = 0; k < 2; ++k)
    frame.files.push_back({dir / name_of(f, k), [f, k, before](const fs::path& staging) {
                             if (before) before(k);
                             write_text(staging, text_of(f, k));
                           }});
  frame.released = [&released] { ++released; };
  return frame;
}

TEST_F(WriterPoolTest, FramesArePublishedInOrderWhateverTheWorkersOrder) {
  std::atomic<int> released{0};
  std::promise<void> go;
  std::shared_future<void> gate = go.get_future().share();
  std::vector<std::uint64_t> published;
  {
    FrameWriterPool pool(3);
    // Frame 0's first file waits until frames 1 and 2 are written: they must not appear before it.
    FrameWriterPool::Frame first = frame_of(
        dir_, 0,
        [gate](std::size_t k) {
          if (k == 0) gate.wait();
        },
        released);
    first.published = [&] { published.push_back(0); };
    pool.submit(std::move(first));
    for (std::uint64_t f = 1; f < 3; ++f) {
      FrameWriterPool::Frame frame = frame_of(dir_, f, {}, released);
      frame.published = [&published, f] { published.push_back(f); };
      pool.submit(std::move(frame));
    }
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (!fs::exists(dir_ / "f2-1.txt.partial") && std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    ASSERT_TRUE(fs::exists(dir_ / "f2-1.txt.partial")) << "frame 2 written meanwhile";
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    EXPECT_FALSE(fs::exists(dir_ / "f1-0.txt")) << "published before frame 0";
    EXPECT_FALSE(fs::exists(dir_ / "f2-0.txt")) << "published before frame 0";
    EXPECT_TRUE(pool.take_written().empty());
    go.set_value();
    pool.finish();
    const std::vector<WrittenFrame> written = pool.take_written();
    ASSERT_EQ(written.size(), 3u);
    for (std::uint64_t f = 0; f < 3; ++f) {
      EXPECT_EQ(written[f].frame, f);
      ASSERT_EQ(written[f].file_sha256.size(), 2u);
      const std::string text = text_of(f, 1);
      EXPECT_EQ(written[f].file_sha256[1], core::sha256_hex(text.data(), text.size()));
      EXPECT_TRUE(fs::exists(dir_ / name_of(f, 0)));
      EXPECT_FALSE(fs::exists(dir_ / (name_of(f, 0) + ".partial")));
    }
  }
  EXPECT_EQ(published, (std::vector<std::uint64_t>{0, 1, 2}));
  EXPECT_EQ(released.load(), 3);
}

TEST_F(WriterPoolTest, AnErrorKeepsTheFramesBeforeItAndRemovesTheRest) {
  for (const int threads : {0, 2}) {
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    std::atomic<int> released{0};
    FrameWriterPool pool(threads);
    bool thrown = false;
    int submitted = 0;
    try {
      for (std::uint64_t f = 0; f < 5; ++f, ++submitted)
        pool.submit(frame_of(
            dir_, f,
            [f, this](std::size_t k) {
              if (f == 2 && k == 1)
                throw std::runtime_error((dir_ / "f2-1.txt").string() + ": No space left on device");
            },
            released));
      pool.finish();
    } catch (const std::runtime_error& e) {
      thrown = true;
      ++submitted;  // the submit that threw took its frame too (and released it)
      EXPECT_NE(std::string(e.what()).find("f2-1.txt: No space left on device"), std::string::npos) << e.what();
    }
    EXPECT_TRUE(thrown) << threads << " threads";
    try {
      pool.finish();
    } catch (const std::runtime_error&) {
    }
    const std::vector<WrittenFrame> written = pool.take_written();
    ASSERT_EQ(written.size(), 2u) << threads << " threads";
    EXPECT_EQ(written[1].frame, 1u);
    for (const auto& entry : fs::directory_iterator(dir_)) {
      const std::string name = entry.path().filename().string();
      EXPECT_TRUE(name.rfind("f0-", 0) == 0 || name.rfind("f1-", 0) == 0) << name << " left behind";
      EXPECT_EQ(entry.path().extension(), ".txt") << name;
    }
    EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 4);
    if (threads == 0) {
      EXPECT_EQ(submitted, 3) << "the simple path stops at the failing frame";
    }
    EXPECT_EQ(released.load(), std::min(submitted, 5)) << "every submitted frame's memory released";
  }
}

}  // namespace
}  // namespace zenith::app::offline
