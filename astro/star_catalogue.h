#pragma once
// The star catalogue, read at run time from a Debian package: stellarium-data's
// Hipparcos/Tycho-based catalogue (/usr/share/stellarium/stars/default/,
// stars_<level>_<type>v<major>_<minor>.cat), in its own binary format. The
// format is defined by Stellarium's sources (Gajdosik 2006–2007,
// src/core/modules/ZoneArray.cpp `ZoneArray::create`, Star.hpp `Star1`/`Star2`);
// this is our own reader of it (docs/night-sky.md, "The catalogue").
//
// A file is, little-endian:
//   header  8 × uint32: magic 0x835f040a, type (0: 28-byte Hipparcos records
//           "Star1", 1: 10-byte records "Star2"; 2, 6-byte "Star3", has no
//           proper motion and is not read), major, minor, level, mag_min
//           (int, millimag), mag_range (millimag), mag_steps
//   zones   20·4^level × uint32: the number of stars in each zone (geodesic_grid.h)
//   stars   the records, zone after zone, brightest first within a zone.
// Star1 (28 bytes): hip (24-bit, 0 = none) | component id (8) ; x0, x1 (int32,
//   tangent-plane position); B−V index (uint8); magnitude index (uint8);
//   spectral index (uint16); dx0, dx1 (int32, proper motion along the zone's
//   axes in the tangent plane, 0.1 mas/yr); parallax (int32, 0.01 mas).
// Star2 (10 bytes, one 80-bit little-endian word, fields from bit 0):
//   x0:20, x1:20, dx0:14, dx1:14 (signed), B−V index:7, magnitude index:5.
// V = (mag_min + index · mag_range / mag_steps) / 1000; B−V = index · 4/127 − 0.5.
// Positions are J2000.0 (ICRS) at epoch J2000.0.
// Proper motion: the records' dx0/dx1, decoded as Stellarium's renderer moves a
// star (Star1::getJ2000Pos: along the zone's axes in the tangent plane), differ
// from the Hipparcos values by up to 20 % and tens of degrees in direction
// (Vega: 93, 342 mas/yr against 200.9, 286.2). stellarium-data ships the
// Hipparcos proper motions as a text table, hip_pm.dat ("HIP pmRA pmDE" in
// mas/yr, μα* = μα cos δ): load_star_catalogue takes them from there for every
// star with a HIP number (all stars to V ≈ 7.5), the records' for the rest.
//
// The catalogue's identity is the SHA-256 of the files read (in order) and the
// magnitude limit: a cluster sends that, never the stars.
#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace zenith::astro {

/// Where stellarium-data installs its catalogue.
inline const std::filesystem::path kStellariumStarDirectory = "/usr/share/stellarium/stars/default";

/// One star (or one component of a double star: Hipparcos lists some components separately).
struct CatalogueStar {
  std::uint32_t hip = 0;             ///< Hipparcos number, 0 for Tycho-only stars
  std::uint8_t component = 0;        ///< component id of a multiple star (0: none)
  double ra_rad = 0.0;               ///< ICRS right ascension at J2000.0, [0, 2π)
  double dec_rad = 0.0;              ///< ICRS declination at J2000.0
  double pm_ra_cosdec_mas_yr = 0.0;  ///< proper motion μα* = μα cos δ [mas/yr]
  double pm_dec_mas_yr = 0.0;        ///< μδ [mas/yr]
  double parallax_mas = 0.0;         ///< 0 where the file has none (Star2 records)
  double v_mag = 0.0;                ///< Johnson V (quantized: 0.05 mag steps below mag 9)
  double b_minus_v = 0.0;            ///< Johnson B−V (quantized: 0.0315 mag steps)
};

struct StarCatalogueOptions {
  std::filesystem::path directory = kStellariumStarDirectory;
  /// Stars brighter than or equal to this V are kept. Files whose brightest
  /// possible star is fainter are not read. [−2, 10.5] (the Debian files reach 10.5).
  double magnitude_limit = 7.0;
  /// Proper motions of Hipparcos stars from the directory's hip_pm.dat (the
  /// new reduction, van Leeuwen 2007) rather than the binary records' fields.
  bool hipparcos_proper_motions = true;
};

struct StarCatalogue {
  std::vector<CatalogueStar> stars;          ///< sorted by V, brightest first
  std::vector<std::filesystem::path> files;  ///< the files read, in order (hip_pm.dat last)
  double magnitude_limit = 0.0;
  std::string
      identity_sha256;  ///< SHA-256 over (each file's name and SHA-256, the limit as text): what a cluster sends
};

/// One file's header.
struct CatalogueFileHeader {
  std::uint32_t type = 0, major = 0, minor = 0, level = 0;
  std::int32_t mag_min_millimag = 0, mag_range_millimag = 0, mag_steps = 0;
  double brightest_mag() const { return mag_min_millimag / 1000.0; }
};

/// Reads one catalogue file, keeping stars with V ≤ `magnitude_limit`. Throws
/// std::runtime_error naming the file and what is wrong (missing, not a
/// catalogue, byte-swapped, unsupported record type, truncated, zone counts
/// that exceed the file).
std::vector<CatalogueStar> read_catalogue_file(const std::filesystem::path& path, double magnitude_limit,
                                               CatalogueFileHeader* header = nullptr);

/// Reads every stars_*.cat file of the directory that can hold a star at or
/// above the limit. Throws std::invalid_argument for a limit outside [−2, 10.5],
/// std::runtime_error when the directory has no catalogue file (naming the
/// Debian package that provides it) or a file is bad.
StarCatalogue load_star_catalogue(const StarCatalogueOptions& options = {});

/// The J2000 unit vector (x toward RA 0, z north) of a right ascension and declination.
glm::dvec3 equatorial_unit_vector(double ra_rad, double dec_rad);

}  // namespace zenith::astro
