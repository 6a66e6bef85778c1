#pragma once
// A short fingerprint of a frame's description: equal for equal descriptions,
// different when any field differs. The cluster's nodes write it to
// presented.log (cluster/node/output_writer.h) and the offline renderer to its
// manifest (offline/offline_manifest.h), so a frame's state is named the same
// way wherever it was rendered, and a resumed offline render compares it.
#include <string>

#include "scene/frame_description.h"

namespace zenith::scene {

/// First 16 hex digits of the SHA-256 of the frame's fields, hashed one by one
/// in this canonical order (no buffer, no protocol):
///
///   frame (u64), show_time_s, camera_position_m x y z, camera_orientation
///   w x y z, exposure, sun_direction x y z, sun_angular_radius_rad (f64 each),
///   the irradiance count (u8) and its values (f64), the atmosphere count (u8)
///   and per atmosphere: body_name's byte count (u16) and UTF-8 bytes,
///   table_hash (32 raw bytes), effective_from_frame (u64); render_flags (u32);
///   the fade's level and colour r g b (f64 each); the sky's flags (u8: bit 0
///   has_time), utc_jd1, utc_jd2 (f64) and star_catalogue (32 raw bytes).
///
/// Integers are big-endian, doubles their IEEE-754 binary64 bit pattern
/// big-endian (so −0 and +0 differ, as they would on the wire). This is the
/// byte sequence of the FrameState payload (docs/protocol.md):
/// tests/scene/frame_digest_test.cpp checks the equality. A field added to the
/// payload is added here too, so a resumed offline render made before it
/// renders its frames again once (their digests differ). A frame
/// within the wire's limits (scene/frame_description.h) is assumed; counts and
/// lengths beyond them are hashed truncated to their width.
std::string frame_digest(const FrameDescription& frame);

}  // namespace zenith::scene
