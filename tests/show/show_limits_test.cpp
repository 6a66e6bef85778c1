// A show's bounds (show/show.h, ShowLimits; core/files.h):
// input that is not a regular file is refused by name at once, a file too
// large for its kind is refused before it is parsed, a track that steps
// through too many table sets stops at the limit, and the plan warns when
// its sets exceed the memory budget.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/files.h"
#include "core/json_reader.h"
#include "show/show.h"
#include "show/table_plan.h"

namespace zenith::show {
namespace {

namespace fs = std::filesystem;
const fs::path kSource = ZENITH_SOURCE_DIR;

class ShowLimitsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("zenith-show-limits-" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  /// A show of the sunset scene whose turbidity goes from 5 to 60 in `step`s over 60 s at 30 fps.
  fs::path turbidity_show(double step) {
    const fs::path path = dir_ / "tiny-step.json";
    std::ofstream(path) << R"({"zenith_show": 1, "name": "tiny-step", "scene": ")"
                        << (kSource / "configs/scenes/earth-sunset.json").string() << R"(", "fps": 30,
      "atmospheres": [{"body": "Earth", "tracks": [{"parameter": "/aerosol/scattering/turbidity", "step": )"
                        << step << R"(, "keys": [{"t_s": 0, "value": 5}, {"t_s": 60, "value": 60}]}]}]})";
    return path;
  }
  static std::string error_of(const fs::path& path, const ShowLimits& limits = {}) {
    try {
      load_show(path, limits);
    } catch (const std::exception& e) {
      return e.what();
    }
    return "";
  }
  fs::path dir_;
};

TEST_F(ShowLimitsTest, AFifoOrADeviceIsRefusedByNameNotReadForever) {
  const fs::path fifo = dir_ / "show.json";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const auto started = std::chrono::steady_clock::now();
  const std::string error = error_of(fifo);  // opening a FIFO with no writer once blocked for good
  EXPECT_LT(std::chrono::steady_clock::now() - started, std::chrono::seconds(2));
  EXPECT_EQ(error.find(fifo.string()), 0u) << error;
  EXPECT_NE(error.find("is a FIFO (named pipe), not a regular file"), std::string::npos) << error;
  const std::string zero = error_of("/dev/zero");  // once an unnamed bad_alloc
  EXPECT_EQ(zero.find("/dev/zero"), 0u) << zero;
  EXPECT_NE(zero.find("is a character device, not a regular file"), std::string::npos) << zero;
  EXPECT_THROW(core::file_bytes("/dev/zero"), std::runtime_error);
  EXPECT_NE(core::unreadable_reason(dir_).find("is a directory"), std::string::npos);
  EXPECT_EQ(core::unreadable_reason(dir_ / "missing.json"), "") << "opening it says it is missing";
}

TEST_F(ShowLimitsTest, AFileLargerThanTheLimitIsRefusedBeforeItIsParsed) {
  const fs::path big = dir_ / "huge-show.json";
  { std::ofstream(big) << "{"; }
  fs::resize_file(big, core::kMaxInputFileBytes + 1);  // sparse: nothing is written, nothing must be read
  const std::string error = error_of(big);
  EXPECT_EQ(error.find(big.string()), 0u) << error;
  EXPECT_NE(error.find("134217729 bytes, more than the 134217728-byte limit of an input file"), std::string::npos)
      << error;
  EXPECT_EQ(core::unreadable_reason(big, core::kMaxInputFileBytes + 1), "") << "the limit is inclusive";
}

// A turbidity step of 0.01 once gave 6 199 table sets (14 GB) without a word.
TEST_F(ShowLimitsTest, ATrackThatStepsThroughTooManyTableSetsStopsAtTheLimit) {
  const std::string error = error_of(turbidity_show(0.01), ShowLimits{16});
  EXPECT_NE(error.find("/atmospheres/0: the tracks of \"Earth\" step through more than 16 lookup-table sets"),
            std::string::npos)
      << error;
  EXPECT_EQ(ShowLimits{}.max_table_sets, 256u) << "docs/shows.md, \"Limits\"";
  const Show coarse = load_show(turbidity_show(5.0), ShowLimits{16});  // 5, 10, …, 60 and the scene's own: 13 sets
  EXPECT_EQ(coarse.frame_count(30.0), 1801u);
}

// A show of 10^7 keys once took 3.5 GB before the key limit refused it: the
// keys are counted before any is read, against a configurable bound.
TEST_F(ShowLimitsTest, ATrackWithMoreKeysThanTheLimitIsRefusedBeforeItsKeysAreRead) {
  const auto show_with_keys = [&](std::size_t count) {
    const fs::path path = dir_ / "many-keys.json";
    std::ofstream out(path);
    out << R"({"zenith_show": 1, "name": "many", "scene": ")" << (kSource / "configs/scenes/earth-sunset.json").string()
        << R"(", "exposure": [)";
    for (std::size_t i = 0; i < count; ++i) out << (i ? "," : "") << R"({"t_s": )" << i << R"(, "exposure": 1})";
    out << "]}";
    return path;
  };
  EXPECT_EQ(ShowLimits{}.max_keys_per_track, 100000u) << "docs/shows.md, \"Limits\"";
  ShowLimits five;
  five.max_keys_per_track = 5;
  const std::string error = error_of(show_with_keys(6), five);
  EXPECT_NE(error.find("/exposure = an array of 6 keys: a track holds at most 5 (--max-keys"), std::string::npos)
      << error;
  EXPECT_EQ(error_of(show_with_keys(5), five), "");
  ShowLimits beyond;
  beyond.max_keys_per_track = 10 * ShowLimits::kMaxKeysPerTrackCeiling;  // the ceiling still holds
  EXPECT_EQ(error_of(show_with_keys(6), beyond), "");
}

TEST_F(ShowLimitsTest, ThePlanWarnsWhenItsSetsExceedTheBudget) {
  TablePlan plan;
  plan.sets.resize(3);
  for (TablePlanEntry& e : plan.sets) e.bytes = 512ull * 1024 * 1024;
  EXPECT_EQ(budget_warning(plan, 4.0), "");
  const std::string warning = budget_warning(plan, 1.0);
  EXPECT_NE(warning.find("warning: the show's 3 lookup-table sets take 1.5 GiB, above the budget of 1.0 GiB"),
            std::string::npos)
      << warning;
}

}  // namespace
}  // namespace zenith::show
