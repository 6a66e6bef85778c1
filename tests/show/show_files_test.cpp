// Every show in configs/shows/ loads and plays: every frame at its own rate is
// finite, the camera stays above every body, and few table sets are needed.
#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "show/show.h"

namespace zenith::show {
namespace {

namespace fs = std::filesystem;

std::vector<fs::path> show_files() {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(fs::path(ZENITH_SOURCE_DIR) / "configs" / "shows"))
    if (entry.path().extension() == ".json") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

TEST(ShowFiles, TheExamplesAreThere) {
  std::vector<std::string> names;
  for (const fs::path& p : show_files()) names.push_back(p.stem().string());
  for (const char* expected : {"earth-limb-pass", "earth-sunrise-dome", "mars-descent", "mars-sunset-aureole",
                               "earth-lunar-eclipse-2029-buenos-aires"})
    EXPECT_NE(std::find(names.begin(), names.end(), expected), names.end()) << expected;
}

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

TEST(ShowFiles, EveryFrameOfEveryShowIsSound) {
  for (const fs::path& path : show_files()) {
    SCOPED_TRACE(path.filename().string());
    const Show show = load_show(path);
    EXPECT_EQ(show.name(), path.stem().string());
    EXPECT_GE(show.duration_s(), 20.0);
    EXPECT_LE(show.duration_s(), 60.0);
    const double fps = show.frame_rate_hz();
    const std::uint64_t frames = show.frame_count(fps);
    double lowest_m = 1e300;
    for (std::uint64_t i = 0; i < frames; ++i) {
      const scene::FrameDescription s = show.state_at(show.frame_time_s(i, fps), i, 0);
      ASSERT_TRUE(finite(s.camera_position_m)) << i;
      ASSERT_NEAR(glm::length(s.camera_orientation), 1.0, 1e-12) << i;
      ASSERT_NEAR(glm::length(s.sun_direction), 1.0, 1e-12) << i;
      ASSERT_TRUE(std::isfinite(s.exposure) && s.exposure > 0.0) << i;
      ASSERT_TRUE(std::isfinite(s.sun_angular_radius_rad) && s.sun_angular_radius_rad > 0.0) << i;
      for (double e : s.sun_irradiance_W_m2_nm) ASSERT_TRUE(std::isfinite(e) && e >= 0.0) << i;
      for (const scene::Body& body : show.scene().bodies) {
        const double altitude = glm::length(s.camera_position_m - body.position_m) - body.radius_m;
        ASSERT_GE(altitude, 0.1) << i << " " << body.name;
        lowest_m = std::min(lowest_m, altitude);
      }
    }
    const std::vector<AtmosphereVersion> versions = show.atmosphere_versions(fps);
    EXPECT_GE(versions.size(), 1u);
    EXPECT_LE(versions.size(), 6u);
    std::printf("  %s: %.0f s, %llu frames at %g fps, %zu table sets, lowest camera %.1f m\n",
                path.filename().string().c_str(), show.duration_s(), static_cast<unsigned long long>(frames), fps,
                versions.size(), lowest_m);
  }
}

}  // namespace
}  // namespace zenith::show
