#pragma once
// The zones of Stellarium's star catalogues: the sphere divided into the 20
// triangles of an icosahedron, each split into 4 at every level (Gajdosik 2006,
// Stellarium src/core/StelGeodesicGrid.cpp). A star's position is stored as two
// integers in the gnomonic (tangent) plane at its zone's centre, along two axes
// of that zone (src/core/modules/ZoneArray.cpp, initTriangle and scaleAxis):
//
//   centre c = normalize(c0 + c1 + c2)   of the zone's three corners,
//   axis0 a0 = normalize(ẑ × c)          (ẑ the J2000 north pole),
//   axis1 a1 = c × a0,
//   direction = normalize(c + s·(x0·a0 + x1·a1)),
//
// with one scale s per file: the largest gnomonic coordinate |μ|/√(1 − |μ|²) of
// any zone corner, divided by the largest stored integer (2³¹ − 1 for the
// Hipparcos records, 2¹⁹ − 1 for the 10-byte records). Zone k of level L is
// child k mod 4 of zone k / 4 of level L − 1, children ordered
//   0: (c0, e2, e1), 1: (e2, c1, e0), 2: (e1, e0, c2), 3: (e0, e1, e2),
// e_i = normalize of the sum of the two corners other than c_i.
// Frame: equatorial J2000 (x toward RA 0, z toward the north pole).
#include <array>
#include <cstddef>
#include <vector>

#include <glm/vec3.hpp>

namespace zenith::astro {

/// One zone's tangent-plane frame (unit vectors, J2000 equatorial).
struct CatalogueZone {
  glm::dvec3 centre, axis0, axis1;
};

struct ZoneGrid {
  std::vector<CatalogueZone> zones;  ///< 20 · 4^level, in the files' order
  double gnomonic_extent = 0.0;      ///< the largest |gnomonic coordinate| of a zone corner (before ÷ MaxPosVal)
};

/// The zones of `level` (0…7; the files use 0–3 up to magnitude 10.5).
/// Throws std::invalid_argument outside that range.
ZoneGrid catalogue_zones(int level);

/// 20 · 4^level.
std::size_t catalogue_zone_count(int level);

}  // namespace zenith::astro
