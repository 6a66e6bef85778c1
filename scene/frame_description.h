#pragma once
// What varies from one frame of a scene to the next: the camera, the sun, the
// exposure, the show time and which lookup-table version each atmosphere uses.
// Shows evaluate into it (show/show.h), renderers apply it to their copy of the
// scene, recordings store it (show/recording_json.h) and the cluster protocol
// sends it as the FrameState message (cluster/protocol/messages.h), byte for byte as
// documented in docs/protocol.md. The static parts of a scene (bodies, albedo,
// the atmospheres' parameters) are in scene::Scene.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

#include "core/sha256.h"

namespace zenith::scene {

/// Identity of a lookup-table set: atmosphere::lookup_table_hash as 32 raw bytes.
using TableHash = core::Sha256Digest;

// Limits of a frame description (the wire and the recordings refuse more).
inline constexpr std::size_t kMaxWavelengths = 64;  ///< sun irradiance samples
inline constexpr std::size_t kMaxAtmospheres = 8;   ///< atmosphere table references
/// Tolerance on |q| − 1 and |sun direction| − 1.
inline constexpr double kUnitTolerance = 1e-6;

/// Bits of FrameDescription::render_flags (also their wire and recording
/// values). Bits outside kKnownRenderFlags must be 0.
enum RenderFlag : std::uint32_t {
  kRenderSunDisc = 1u << 0,
  kRenderLimbDarkening = 1u << 1,
  kRenderMultipleScattering = 1u << 2,
  kRenderEclipses = 1u << 3,
  kRenderBodies = 1u << 4,
};
inline constexpr std::uint32_t kKnownRenderFlags = (1u << 5) - 1;

/// Which lookup-table set an atmosphere uses, from which frame on.
struct AtmosphereTableRef {
  std::string body_name;                   ///< the scene's body (1..64 UTF-8 bytes on the wire)
  TableHash table_hash{};                  ///< atmosphere::lookup_table_hash as 32 raw bytes
  std::uint64_t effective_from_frame = 0;  ///< renderers switch tables at this frame (all at once)
  bool operator==(const AtmosphereTableRef&) const = default;
};

/// A fade of every output toward a colour, as an operator runs a dome
/// (docs/operator.md, "Fades"): level 0 shows the picture, 1 only the colour
/// (black at level 1: a blackout). Display-linear: applied after tone mapping,
/// before the blend mask and black level (render/display/display_encoder.h).
struct FadeState {
  double level = 0.0;      ///< in [0, 1]
  glm::dvec3 colour{0.0};  ///< display-linear RGB, each in [0, 1]
  bool operator==(const FadeState&) const = default;
};
inline constexpr double kMaxFadeLevel = 1.0;

/// The sky by date of a frame (docs/protocol.md, "FrameState",
/// the sky fields): the instant it shows, so that every node of a cluster
/// places the same stars, Sun and Moon at the same frame, and the identity of
/// the star catalogue they are drawn from (never its data: each node reads
/// its own copy of stellarium-data and checks that it is the same).
struct SkyFrame {
  bool has_time = false;  ///< the scene has a sky clock ("time" and "site"); false: the fields below are 0
  /// UTC as ERFA's two-part quasi Julian date (astro::AstroTime::utc()), when has_time.
  double utc_jd1 = 0.0, utc_jd2 = 0.0;
  /// astro::StarCatalogue::identity_sha256 as 32 raw bytes; all zero: not checked.
  core::Sha256Digest star_catalogue{};
  bool operator==(const SkyFrame&) const = default;
};

/// Everything that varies per frame. Vectors in the scene's world frame
/// (scene/scene.h). Every double must be finite.
struct FrameDescription {
  std::uint64_t frame = 0;
  double show_time_s = 0.0;
  glm::dvec3 camera_position_m{0.0};
  glm::dquat camera_orientation{1, 0, 0, 0};    ///< camera → world, unit
  double exposure = 10.0;                       ///< radiance multiplier before tone mapping, > 0
  glm::dvec3 sun_direction{0, 0, 1};            ///< unit, toward the sun
  double sun_angular_radius_rad = 0.0;          ///< ≥ 0
  std::vector<double> sun_irradiance_W_m2_nm;   ///< ≤ kMaxWavelengths values, each ≥ 0
  std::vector<AtmosphereTableRef> atmospheres;  ///< ≤ kMaxAtmospheres
  std::uint32_t render_flags = 0;               ///< RenderFlag bits
  FadeState fade;                               ///< the operator's fade at this frame's present
  SkyFrame sky;  ///< the sky's date and catalogue (its own struct: the night sky's fields)
  bool operator==(const FrameDescription&) const = default;
};

}  // namespace zenith::scene
