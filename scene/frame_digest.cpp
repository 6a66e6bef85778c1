#include "scene/frame_digest.h"

#include <array>
#include <bit>
#include <cstdint>

#include "core/sha256_stream.h"

namespace zenith::scene {
namespace {

/// Feeds fields to a SHA-256 stream in the canonical encoding of frame_digest.
class FieldHasher {
 public:
  /// The low `bytes` bytes of `v`, most significant first.
  void unsigned_be(std::uint64_t v, int bytes) {
    std::array<std::uint8_t, 8> be{};
    for (int i = 0; i < bytes; ++i)
      be[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(v >> (8 * (bytes - 1 - i)));
    stream_.update(be.data(), static_cast<std::size_t>(bytes));
  }
  void f64(double v) { unsigned_be(std::bit_cast<std::uint64_t>(v), 8); }
  void raw(const void* data, std::size_t bytes) { stream_.update(data, bytes); }
  std::string hex16() { return core::to_hex(stream_.digest()).substr(0, 16); }

 private:
  core::Sha256Stream stream_;
};

}  // namespace

std::string frame_digest(const FrameDescription& frame) {
  const glm::dvec3& c = frame.camera_position_m;
  const glm::dquat& q = frame.camera_orientation;
  const glm::dvec3& sun = frame.sun_direction;
  const double reals[] = {
      frame.show_time_s,           c.x, c.y, c.z, q.w, q.x, q.y, q.z, frame.exposure, sun.x, sun.y, sun.z,
      frame.sun_angular_radius_rad};
  FieldHasher h;
  h.unsigned_be(frame.frame, 8);
  for (const double v : reals) h.f64(v);
  h.unsigned_be(frame.sun_irradiance_W_m2_nm.size(), 1);
  for (const double e : frame.sun_irradiance_W_m2_nm) h.f64(e);
  h.unsigned_be(frame.atmospheres.size(), 1);
  for (const AtmosphereTableRef& a : frame.atmospheres) {
    h.unsigned_be(a.body_name.size(), 2);
    h.raw(a.body_name.data(), a.body_name.size());
    h.raw(a.table_hash.data(), a.table_hash.size());
    h.unsigned_be(a.effective_from_frame, 8);
  }
  h.unsigned_be(frame.render_flags, 4);
  h.f64(frame.fade.level);
  for (int i = 0; i < 3; ++i) h.f64(frame.fade.colour[i]);
  h.unsigned_be(frame.sky.has_time ? 1 : 0, 1);
  h.f64(frame.sky.utc_jd1);
  h.f64(frame.sky.utc_jd2);
  h.raw(frame.sky.star_catalogue.data(), frame.sky.star_catalogue.size());
  return h.hex16();
}

}  // namespace zenith::scene
