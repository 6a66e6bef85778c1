// The offline render's manifest and resume rule (offline/offline_manifest.h) and
// its file naming and settings keys (offline/offline_render.h).
#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <string>

#include "offline/offline_manifest.h"
#include "offline/offline_render.h"

namespace zenith::app::offline {
namespace {

/// A fresh folder, removed with its contents.
class Folder {
 public:
  Folder() {
    const ::testing::TestInfo* test = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::temp_directory_path() /
            ("zenith-offline-" + std::to_string(::getpid()) + "-" + std::string(test->name()));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~Folder() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

void write_text(const std::filesystem::path& path, const std::string& text) {
  std::filesystem::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary | std::ios::trunc) << text;
}

constexpr const char* kDigest = "0123456789abcdef";
constexpr const char* kPngKey = "aaaaaaaaaaaaaaaa";
constexpr const char* kExrKey = "bbbbbbbbbbbbbbbb";

/// A folder with frame 3's two files and a manifest entry for them.
struct Fixture {
  Folder folder;
  Manifest manifest;
  std::vector<ExpectedFile> expected{{"dome/dome.000003.png", kPngKey}, {"dome/dome.000003.exr", kExrKey}};

  Fixture() {
    write_text(folder.path() / expected[0].path, "png bytes");
    write_text(folder.path() / expected[1].path, "exr bytes");
    manifest.frames[3] = {kDigest,
                          {{expected[0].path, kPngKey, file_sha256(folder.path() / expected[0].path)},
                           {expected[1].path, kExrKey, file_sha256(folder.path() / expected[1].path)}}};
  }
  FrameCheck check(const std::vector<ExpectedFile>& files) const {
    return check_frame(manifest, 3, kDigest, files, folder.path());
  }
};

TEST(OfflineManifest, FileSha256IsTheDigestOfTheBytes) {
  Folder folder;
  write_text(folder.path() / "abc", "abc");
  EXPECT_EQ(file_sha256(folder.path() / "abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_THROW(file_sha256(folder.path() / "missing"), std::runtime_error);
}

TEST(OfflineManifest, RoundTripsThroughItsFile) {
  Fixture f;
  f.manifest.run = {{"fps", 30}, {"show", {{"name", "test"}}}};
  f.manifest.frames[0] = {"fedcba9876543210", {}};
  const std::filesystem::path path = f.folder.path() / kManifestFileName;
  EXPECT_TRUE(read_manifest(path).frames.empty());  // no file yet: an empty manifest
  write_manifest(path, f.manifest);
  EXPECT_FALSE(std::filesystem::exists(f.folder.path() / "manifest.json.partial"));
  const Manifest back = read_manifest(path);
  EXPECT_EQ(back, f.manifest);
  EXPECT_EQ(back.frames.at(3).files.at(1).path, "dome/dome.000003.exr");
  EXPECT_EQ(to_json(back).at("zenith_offline_render"), kManifestFormatVersion);
}

TEST(OfflineManifest, MalformedManifestsNameTheKey) {
  auto message_of = [](const nlohmann::json& json) {
    try {
      manifest_from_json(json, "m.json");
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message_of({{"zenith_offline_render", 2}, {"frames", nlohmann::json::array()}})
                .find("m.json: /zenith_offline_render: 2: unsupported manifest version"),
            std::string::npos);
  EXPECT_NE(message_of({{"frames", nlohmann::json::array()}}).find("/zenith_offline_render: missing"),
            std::string::npos);
  const nlohmann::json bad_sha = {
      {"zenith_offline_render", 1},
      {"frames",
       {{{"frame", 4},
         {"state_digest", kDigest},
         {"files", {{{"path", "a/a.000004.png"}, {"settings_key", kPngKey}, {"sha256", "xyz"}}}}}}}};
  EXPECT_NE(message_of(bad_sha).find("/frames/0/files/0/sha256: expected 64 lowercase hex digits"), std::string::npos);
  const nlohmann::json twice = {{"zenith_offline_render", 1},
                                {"frames",
                                 {{{"frame", 4}, {"state_digest", kDigest}, {"files", nlohmann::json::array()}},
                                  {{"frame", 4}, {"state_digest", kDigest}, {"files", nlohmann::json::array()}}}}};
  EXPECT_NE(message_of(twice).find("/frames/1/frame: frame 4 listed twice"), std::string::npos);

  Folder folder;
  write_text(folder.path() / "manifest.json", "{\"zenith_offline_render\": 1, ");
  try {
    read_manifest(folder.path() / "manifest.json");
    FAIL() << "a truncated manifest was read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("not a valid manifest"), std::string::npos) << e.what();
  }
}

TEST(OfflineResume, SkipsAFrameWhoseFilesAreVerified) {
  Fixture f;
  const FrameCheck c = f.check(f.expected);
  EXPECT_TRUE(c.skip) << c.reason;
  EXPECT_EQ(c.files, f.manifest.frames.at(3).files);
}

TEST(OfflineResume, RendersAFrameNotInTheManifest) {
  Fixture f;
  const FrameCheck c = check_frame(f.manifest, 4, kDigest, f.expected, f.folder.path());
  EXPECT_FALSE(c.skip);
  EXPECT_EQ(c.reason, "not in the manifest");
}

TEST(OfflineResume, RendersAFrameWhoseStateChanged) {
  Fixture f;
  const FrameCheck c = check_frame(f.manifest, 3, "0123456789abcdee", f.expected, f.folder.path());
  EXPECT_FALSE(c.skip);
  EXPECT_NE(c.reason.find("its state changed"), std::string::npos) << c.reason;
}

TEST(OfflineResume, RendersAFrameWithAMissingFile) {
  Fixture f;
  std::filesystem::remove(f.folder.path() / "dome/dome.000003.exr");
  const FrameCheck c = f.check(f.expected);
  EXPECT_FALSE(c.skip);
  EXPECT_EQ(c.reason, "dome/dome.000003.exr: missing");
}

TEST(OfflineResume, RendersAFrameWhoseFileChangedOnDisk) {
  Fixture f;
  write_text(f.folder.path() / "dome/dome.000003.png", "png bytez");  // same size, other bytes
  const FrameCheck c = f.check(f.expected);
  EXPECT_FALSE(c.skip);
  EXPECT_NE(c.reason.find("dome/dome.000003.png: changed on disk"), std::string::npos) << c.reason;
}

TEST(OfflineResume, RendersAFrameMadeWithOtherSettings) {
  Fixture f;
  std::vector<ExpectedFile> expected = f.expected;
  expected[1].settings_key = "cccccccccccccccc";  // e.g. --exr-type float instead of half
  const FrameCheck c = f.check(expected);
  EXPECT_FALSE(c.skip);
  EXPECT_EQ(c.reason, "dome/dome.000003.exr: rendered with other settings");
}

TEST(OfflineResume, AFormatOrOutputAddedRendersTheFrameOneRemovedDoesNot) {
  Fixture f;
  std::vector<ExpectedFile> more = f.expected;
  more.push_back({"wall/wall.000003.png", kPngKey});
  const FrameCheck added = f.check(more);
  EXPECT_FALSE(added.skip);
  EXPECT_EQ(added.reason, "wall/wall.000003.png: not in the manifest");

  const FrameCheck removed = f.check({f.expected[1]});  // --format exr only
  EXPECT_TRUE(removed.skip) << removed.reason;
  ASSERT_EQ(removed.files.size(), 1u);
  EXPECT_EQ(removed.files[0].path, "dome/dome.000003.exr");
}

TEST(OfflineLayout, FrameFilesAreNumberedPerOutput) {
  EXPECT_EQ(frame_file_path("dome", 12, ImageFormat::png), "dome/dome.000012.png");
  EXPECT_EQ(frame_file_path("p2", 0, ImageFormat::exr), "p2/p2.000000.exr");
  EXPECT_EQ(frame_file_path("dome", 1234567, ImageFormat::png), "dome/dome.1234567.png");
  EXPECT_EQ(frame_file_path("dome", 7, ImageFormat::tiff), "dome/dome.000007.tif");
  EXPECT_EQ(frame_file_path("dome", 7, ImageFormat::png16), "dome/dome.000007.png");
}

TEST(OfflineLayout, FrameNamePatternsNumberFromTheStartNumber) {
  const FileNaming studio = parse_file_naming("show.%04d.png", 1);  // the extension is the format's
  EXPECT_EQ(studio.pattern, "show.%04d");
  EXPECT_EQ(frame_file_path("dome", 0, ImageFormat::png, studio), "dome/show.0001.png");
  EXPECT_EQ(frame_file_path("dome", 41, ImageFormat::exr, studio), "dome/show.0042.exr");
  EXPECT_EQ(frame_file_path("dome", 12345, ImageFormat::tiff, studio), "dome/show.12346.tif");  // wider than 4
  const FileNaming plain = parse_file_naming("{output}_%d", 100);
  EXPECT_EQ(frame_file_path("left", 5, ImageFormat::png, plain), "left/left_105.png");
  EXPECT_EQ(parse_file_naming("{output}.%06d", 0), FileNaming{});
  for (const char* bad : {"show.png", "show.%06d.%d", "a/b.%04d", "show.%5d", "show.%06x"}) {
    try {
      parse_file_naming(bad, 0);
      FAIL() << bad << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(std::string("--frame-name '") + bad + "'"), std::string::npos) << e.what();
    }
  }
}

TEST(OfflineLayout, FormatsParseAndRefuseWithTheOption) {
  EXPECT_EQ(parse_formats("png,exr"), (std::vector<ImageFormat>{ImageFormat::png, ImageFormat::exr}));
  EXPECT_EQ(parse_formats("exr"), (std::vector<ImageFormat>{ImageFormat::exr}));
  EXPECT_EQ(parse_formats("png16,tiff,exr"),
            (std::vector<ImageFormat>{ImageFormat::png16, ImageFormat::tiff, ImageFormat::exr}));
  for (const auto& [bad, why] : std::vector<std::pair<std::string, std::string>>{
           {"gif", "'gif' is not a format"}, {"png,png", "png twice"}, {"png,png16", "png and png16"}, {"", "''"}}) {
    try {
      parse_formats(bad);
      FAIL() << bad << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("--format '" + bad + "': "), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
    }
  }
}

TEST(OfflineLayout, SettingsKeysChangeWithWhatShapesTheBytes) {
  RenderJob job;
  job.settings = "scene sha256 1234; tables small orders 4; colour auto";
  job.png_settings = "tone exponential";
  job.exr_settings = "pixels half";
  const OutputSpec dome{"fisheye", 48, 48, "fisheye 180 deg", std::nullopt};
  const std::string png = settings_key(job, dome, ImageFormat::png), exr = settings_key(job, dome, ImageFormat::exr);
  EXPECT_EQ(png.size(), 16u);
  EXPECT_NE(png, exr);
  EXPECT_EQ(png, settings_key(job, dome, ImageFormat::png));  // deterministic

  RenderJob float_exr = job;
  float_exr.exr_settings = "pixels float";
  EXPECT_EQ(settings_key(float_exr, dome, ImageFormat::png), png);  // the PNG is unaffected
  EXPECT_NE(settings_key(float_exr, dome, ImageFormat::exr), exr);
  RenderJob paper = job;
  paper.settings = "scene sha256 1234; tables paper orders 4; colour auto";
  EXPECT_NE(settings_key(paper, dome, ImageFormat::png), png);
  const OutputSpec bigger{"fisheye", 64, 64, "fisheye 180 deg", std::nullopt};
  EXPECT_NE(settings_key(job, bigger, ImageFormat::png), png);
}

}  // namespace
}  // namespace zenith::app::offline
