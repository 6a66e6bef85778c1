#pragma once
// The Moon's albedo map (docs/night-sky.md, "The Moon's
// face"): stellarium-data's textures/moon.png, read at run time, as relative
// albedo for the disc of shaders/render/night_sky.comp.
//
// The file: 1024 × 512, 8-bit sRGB, equirectangular in selenographic
// coordinates (USGS Astrogeology and Clementine mosaics, public domain:
// /usr/share/doc/stellarium-data/CREDITS.md.gz §4.4). Column x spans east
// longitude −180° + 360° x / W to −180° + 360° (x + 1) / W (the near side's
// centre, 0°, in the middle; east, Mare Crisium at 59° E, to the right), row y
// latitude 90° − 180° y / H down to 90° − 180° (y + 1) / H (north at the top):
// checked on the maria (Crisium at 17° N 59° E, Orientale's ring at 20° S
// 95° W, Tycho at 43° S 11° W). Its values: no calibration is published. The
// file carries ImageMagick's default gAMA 1/2.2 tag, but decoded that way the
// maria come out at 0.19–0.23 of the highlands' albedo and the far side at 1.84×
// the near side's mean, where the Moon's maria reflect about half as much as its
// highlands (normal albedo ~0.07–0.10 against ~0.11–0.18: Heiken, Vaniman &
// French, "Lunar Sourcebook", 1991, §10.2); read as linear in albedo (code /
// 255) they come out at 0.47 (Mare Crisium against the highlands south of it)
// and 1.36. So the code values are taken as linear relative albedo: the
// decoded image is re-encoded to its codes (image::srgb_encode, exact), reduced
// to luminance (Rec. 709 weights; the map is grey to a few percent, the Moon's
// colour is astro/moon_photometry.h's), and divided by the map's photometric
// mean over the near side (the full Moon without libration: each point weighted
// by its projected area, μ dA), so the stored texels are albedo relative to
// the Moon's mean.
//
// Normalization per frame (moon_disc_mean_albedo): the disc's brightness by
// phase is the Moon's measured integral phase law (astro/moon_photometry.h),
// which already includes the maria; the map only redistributes it over the
// disc. The disc's radiance is divided by the map's mean over the visible,
// lit disc weighted as the Lommel–Seeliger law weights it, so the disc
// carries the same irradiance as the point source and the moonlit sky.
#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "astro/sky_data_identity.h"

namespace zenith::render {

using astro::kStellariumMoonMap;

/// The Moon's body-fixed axes (astro::MoonAxes) in the world frame: x toward
/// selenographic (0°, 0°), y toward (90° E, 0°), z toward the north pole.
using MoonWorldAxes = std::array<glm::dvec3, 3>;

class MoonAlbedoMap {
 public:
  /// Reads an equirectangular map as above (PNG or OpenEXR, image::read_image).
  /// Throws std::runtime_error naming the file (missing, unreadable, not 2:1,
  /// black on the near side).
  static MoonAlbedoMap load(const std::filesystem::path& path);
  /// 1 everywhere: the fallback when the file is missing.
  static MoonAlbedoMap uniform();

  int width() const { return width_; }
  int height() const { return height_; }
  /// Relative albedo, row 0 at the north pole, column 0 at −180°, x fastest.
  const std::vector<float>& texels() const { return texels_; }
  bool is_uniform() const { return identity_sha256_.empty(); }
  /// The largest texel (a bound on the disc's brightness relative to its mean).
  double largest() const { return largest_; }
  /// SHA-256 of the file's bytes ("" for the uniform map: astro::moon_map_identity),
  /// joined with the catalogue's in what a cluster compares (astro/sky_data_identity.h).
  const std::string& identity_sha256() const { return identity_sha256_; }
  /// Bilinear relative albedo at a selenographic point, from a copy box-filtered
  /// to 1.4° texels (what the disc's mean needs; the GPU samples the full map).
  double coarse_at(double longitude_rad, double latitude_rad) const;

 private:
  int width_ = 1, height_ = 1;
  std::vector<float> texels_{1.0f};
  int coarse_width_ = 1, coarse_height_ = 1;
  std::vector<float> coarse_{1.0f};
  double largest_ = 1.0;
  std::string identity_sha256_;
};

/// The photometric mean of the map over the disc seen from `toward_moon` (unit,
/// observer → Moon) lit from `toward_sun` (unit, the Sun's direction, taken as
/// the same from the Moon as from the observer, as the shader takes it):
///   ā = ∫ a(n) μ0/(μ0 + μ) dA⊥ / ∫ μ0/(μ0 + μ) dA⊥
/// over the lit part of the disc (dA⊥ the projected area, μ = n·(−toward_moon),
/// μ0 = n·toward_sun), on a 96 × 96 grid across the disc. 1 when nothing is lit.
double moon_disc_mean_albedo(const MoonAlbedoMap& map, const MoonWorldAxes& axes, const glm::dvec3& toward_moon,
                             const glm::dvec3& toward_sun);

}  // namespace zenith::render
