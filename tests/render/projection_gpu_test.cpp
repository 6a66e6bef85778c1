// shaders/projection.glsl against the CPU projections of warp/ (planar,
// fisheye, cylindrical, equirectangular, cube face): the ray of every pixel centre, computed in float on the GPU (Mesa
// llvmpipe without one) from GpuProjection's 16 floats, equals the CPU's double ray within 2e-6 rad; a fisheye's pixels
// without a ray agree except within 1e-4 px of the circle. Built as warp_gpu_tests (tests/warp/CMakeLists.txt).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "render/gl/egl_context.h"
#include "render/gl/gl_error.h"
#include "render/gl/shader_program.h"
#include "render/gl/texture.h"
#include "render/shader_bindings.h"
#include "tests/render/test_shaders.h"
#include "warp/cube_face_projection.h"
#include "warp/cylindrical_projection.h"
#include "warp/equirectangular_projection.h"
#include "warp/fisheye_projection.h"
#include "warp/planar_projection.h"

namespace zenith::render {
namespace {

using warp::CubeFace;
using warp::CubeFaceProjection;
using warp::CylindricalParameters;
using warp::CylindricalProjection;
using warp::EquirectangularParameters;
using warp::EquirectangularProjection;
using warp::FisheyeParameters;
using warp::FisheyeProjection;
using warp::PlanarFrustum;
using warp::PlanarProjection;
using warp::Projection;

constexpr double kMaxAngleRad = 2e-6;
constexpr double kRimSlackPx = 1e-4;

/// Runs test_projection.comp for `projection`: rgba per pixel, rgb the ray, a = 1 where there is one.
std::vector<float> gpu_rays(const gl::ShaderProgram& program, const Projection& projection) {
  const warp::GpuProjection g = projection.gpu();
  EXPECT_TRUE(program.set_uniform("projection_kind", static_cast<int>(g.kind)));
  for (int i = 0; i < 4; ++i)
    EXPECT_TRUE(program.set_uniform("projection_params[" + std::to_string(i) + "]", g.params[i])) << i;
  gl::Texture image = gl::Texture::create_2d(gl::TextureFormat::rgba32f, projection.width(), projection.height());
  image.bind_image(binding::kOutputImage, gl::ImageAccess::write_only);
  program.dispatch_covering(projection.width(), projection.height());
  std::vector<float> out = image.read();
  gl::check_gl_error("test_projection.comp");
  return out;
}

struct Case {
  std::string name;
  std::shared_ptr<const Projection> projection;
};

class ProjectionGpu : public ::testing::Test {
 protected:
  gl::HeadlessContext context_;
};

TEST_F(ProjectionGpu, RaysMatchTheCpuProjections) {
  const gl::ShaderProgram program = testing::load_test_compute_program("test_projection.comp");
  std::printf("renderer: %s\n", context_.renderer().c_str());
  auto planar = [](int w, int h, PlanarFrustum f) { return std::make_shared<PlanarProjection>(w, h, f); };
  auto fisheye = [](int w, int h, FisheyeParameters p) { return std::make_shared<FisheyeProjection>(w, h, p); };
  auto cylinder = [](int w, int h, CylindricalParameters p) {
    return std::make_shared<CylindricalProjection>(w, h, p);
  };
  auto equirect = [](int w, int h, EquirectangularParameters p) {
    return std::make_shared<EquirectangularProjection>(w, h, p);
  };
  auto cube = [](int size, CubeFace face) { return std::make_shared<CubeFaceProjection>(size, face); };
  const std::vector<Case> cases = {
      {"planar symmetric 64×48", std::make_shared<PlanarProjection>(PlanarProjection::symmetric(64, 48, 90.0))},
      {"planar asymmetric 65×65", planar(65, 65, {-20.0, 45.0, -10.0, 30.0})},
      {"planar rotated 64×48", planar(64, 48, {-30.0, 25.0, -15.0, 20.0, 35.0, -20.0, 15.0})},
      {"planar off-axis 65×65", planar(65, 65, {10.0, 40.0, 5.0, 30.0, -100.0, 60.0, -170.0})},
      {"fisheye 180° 64×48", fisheye(64, 48, {})},
      {"fisheye 180° 65×65", fisheye(65, 65, {})},
      {"fisheye 210° tilted 30° 65×65", fisheye(65, 65, {.fov_deg = 210.0, .tilt_deg = 30.0, .rotation_deg = 20.0})},
      {"fisheye 360° 64×48", fisheye(64, 48, {.fov_deg = 360.0})},
      {"fisheye 360° 65×65", fisheye(65, 65, {.fov_deg = 360.0, .tilt_deg = -60.0})},
      {"fisheye cropped 64×48", fisheye(64, 48,
                                        {.fov_deg = 200.0,
                                         .tilt_deg = 15.0,
                                         .centre_x_px = 30.0,
                                         .centre_y_px = 40.0,
                                         .radius_px = 37.5,
                                         .rotation_deg = -45.0})},
      {"cylindrical 360° 128×32", cylinder(128, 32, {})},
      {"cylindrical 360° asymmetric 101×37", cylinder(101, 37, {.down_deg = -20.0, .up_deg = 88.0})},
      {"cylindrical 200° turned 96×40", cylinder(96, 40,
                                                 {.horizontal_fov_deg = 200.0,
                                                  .down_deg = -30.0,
                                                  .up_deg = 40.0,
                                                  .yaw_deg = 35.0,
                                                  .pitch_deg = -20.0,
                                                  .roll_deg = 15.0})},
      {"equirectangular 360×180 128×64", equirect(128, 64, {})},
      {"equirectangular 360×180 101×37", equirect(101, 37, {})},
      {"equirectangular over the seam 96×40", equirect(96, 40, {120.0, 240.0, -10.0, 60.0})},
      {"equirectangular 0..360 64×32", equirect(64, 32, {0.0, 360.0, -90.0, 90.0})},
      {"cube +x 64", cube(64, CubeFace::positive_x)},
      {"cube -x 64", cube(64, CubeFace::negative_x)},
      {"cube +y 64", cube(64, CubeFace::positive_y)},
      {"cube -y 64", cube(64, CubeFace::negative_y)},
      {"cube +z 65", cube(65, CubeFace::positive_z)},
      {"cube -z 65", cube(65, CubeFace::negative_z)},
  };
  for (const Case& c : cases) {
    const Projection& p = *c.projection;
    const auto* circle = dynamic_cast<const FisheyeProjection*>(&p);
    const std::vector<float> gpu = gpu_rays(program, p);
    ASSERT_EQ(gpu.size(), static_cast<std::size_t>(p.width() * p.height() * 4)) << c.name;
    double worst = 0.0;
    int compared = 0, without_ray = 0;
    for (int j = 0; j < p.height(); ++j)
      for (int i = 0; i < p.width(); ++i) {
        const double x = i + 0.5, y = j + 0.5;
        const float* texel = &gpu[static_cast<std::size_t>(4 * (i + p.width() * j))];
        const bool gpu_valid = texel[3] == 1.0f;
        const std::optional<glm::dvec3> cpu = p.ray(x, y);
        if (cpu.has_value() != gpu_valid) {
          ASSERT_TRUE(circle) << c.name << ": pixel " << i << ", " << j << " has no ray on one side";
          EXPECT_LT(std::abs(std::hypot(x - circle->centre_x_px(), y - circle->centre_y_px()) - circle->radius_px()),
                    kRimSlackPx)
              << c.name << ": pixel " << i << ", " << j
              << (gpu_valid ? " has a ray on the GPU only" : " has a ray on the CPU only");
          continue;
        }
        if (!cpu) {
          ++without_ray;
          continue;
        }
        const glm::dvec3 g(texel[0], texel[1], texel[2]);
        const double angle = std::atan2(glm::length(glm::cross(*cpu, g)), glm::dot(*cpu, g));
        EXPECT_LT(angle, kMaxAngleRad) << c.name << ": pixel " << i << ", " << j;
        worst = std::max(worst, angle);
        ++compared;
      }
    EXPECT_GT(compared, p.width() * p.height() / 2) << c.name;
    if (!circle) {
      EXPECT_EQ(without_ray, 0) << c.name;
    }
    std::printf("%-32s %5d rays, %4d pixels without one: max GPU-CPU angle %.3g rad\n", c.name.c_str(), compared,
                without_ray, worst);
  }
}

}  // namespace
}  // namespace zenith::render
