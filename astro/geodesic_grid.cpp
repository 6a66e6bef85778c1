#include "astro/geodesic_grid.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

namespace zenith::astro {
namespace {

using glm::dvec3;

// The icosahedron of StelGeodesicGrid: corners (±a, ±b, 0), (0, ±a, ±b),
// (±b, 0, ±a) with b = 1/√(1 + G²), a = bG, G the golden ratio, and its 20
// faces in the catalogue's zone order (counter-clockwise seen from outside).
struct Icosahedron {
  std::array<dvec3, 12> corner;
  static constexpr int face[20][3] = {{1, 0, 10}, {0, 1, 9},  {0, 9, 6},   {9, 8, 6},   {0, 7, 10},
                                      {6, 7, 0},  {7, 6, 3},  {6, 8, 3},   {11, 10, 7}, {7, 3, 11},
                                      {3, 2, 11}, {2, 3, 8},  {10, 11, 4}, {2, 4, 11},  {5, 4, 2},
                                      {2, 8, 5},  {4, 1, 10}, {4, 5, 1},   {5, 9, 1},   {8, 9, 5}};
  Icosahedron() {
    const double g = 0.5 * (1.0 + std::sqrt(5.0));
    const double b = 1.0 / std::sqrt(1.0 + g * g), a = b * g;
    corner = {dvec3{a, -b, 0}, {a, b, 0},   {-a, b, 0}, {-a, -b, 0}, {0, a, -b}, {0, a, b},
              {0, -a, b},      {0, -a, -b}, {-b, 0, a}, {b, 0, a},   {b, 0, -a}, {-b, 0, -a}};
  }
};

void subdivide(int level, int target, const dvec3& c0, const dvec3& c1, const dvec3& c2, ZoneGrid& grid) {
  if (level == target) {
    CatalogueZone z;
    z.centre = glm::normalize(c0 + c1 + c2);
    z.axis0 = glm::normalize(glm::cross(dvec3{0, 0, 1}, z.centre));
    z.axis1 = glm::cross(z.centre, z.axis0);
    for (const dvec3* c : {&c0, &c1, &c2}) {
      const dvec3 d = *c - z.centre;
      const double mu0 = glm::dot(d, z.axis0), mu1 = glm::dot(d, z.axis1);
      const double f = 1.0 / std::sqrt(1.0 - mu0 * mu0 - mu1 * mu1);
      grid.gnomonic_extent = std::max({grid.gnomonic_extent, std::abs(mu0) * f, std::abs(mu1) * f});
    }
    grid.zones.push_back(z);
    return;
  }
  const dvec3 e0 = glm::normalize(c1 + c2), e1 = glm::normalize(c2 + c0), e2 = glm::normalize(c0 + c1);
  subdivide(level + 1, target, c0, e2, e1, grid);
  subdivide(level + 1, target, e2, c1, e0, grid);
  subdivide(level + 1, target, e1, e0, c2, grid);
  subdivide(level + 1, target, e0, e1, e2, grid);
}

}  // namespace

std::size_t catalogue_zone_count(int level) { return std::size_t(20) << (2 * level); }

ZoneGrid catalogue_zones(int level) {
  if (level < 0 || level > 7)
    throw std::invalid_argument("catalogue zone level " + std::to_string(level) + ": must be in [0, 7]");
  static const Icosahedron ico;
  ZoneGrid grid;
  grid.zones.reserve(catalogue_zone_count(level));
  // Depth-first in child order gives zone k of level L at index k (k = 4·parent + child).
  for (const auto& f : Icosahedron::face)
    subdivide(0, level, ico.corner[f[0]], ico.corner[f[1]], ico.corner[f[2]], grid);
  return grid;
}

}  // namespace zenith::astro
