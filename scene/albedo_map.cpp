#include "scene/albedo_map.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <sstream>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "core/parallel_for.h"
#include "core/sha256.h"
#include "core/units.h"

namespace zenith::scene {
namespace {

using core::kDeg;
using core::kPi;
using glm::dvec3;

// ------------------------------------------------------------------ hashing

/// A 32-bit integer finalizer (xor-shift / multiply rounds; the constants are
/// those of Wellons' "lowbias32", public domain): every input bit affects every
/// output bit, which lattice noise needs so neighbouring cells are unrelated.
std::uint32_t mix32(std::uint32_t h) {
  h ^= h >> 16;
  h *= 0x7feb352du;
  h ^= h >> 15;
  h *= 0x846ca68bu;
  h ^= h >> 16;
  return h;
}

/// Hash of an integer lattice point and a seed.
std::uint32_t hash_cell(int x, int y, int z, std::uint32_t seed) {
  std::uint32_t h = mix32(seed ^ 0x9e3779b9u);
  h = mix32(h ^ static_cast<std::uint32_t>(x));
  h = mix32(h ^ (static_cast<std::uint32_t>(y) * 0x85ebca77u));
  h = mix32(h ^ (static_cast<std::uint32_t>(z) * 0xc2b2ae3du));
  return h;
}

/// A uniform number in [0, 1) from a hash and a small stream index.
double uniform(std::uint32_t h, std::uint32_t stream) {
  return double(mix32(h + stream * 0x632be5abu)) * (1.0 / 4294967296.0);
}

/// A seed for a sub-field (continents, moisture, ...) of a map's seed.
std::uint32_t field_seed(std::uint32_t seed, std::uint32_t field) { return mix32(seed * 0x2545f491u + field); }

// ------------------------------------------------------------------ noise

/// Quintic fade 6t⁵ − 15t⁴ + 10t³: C² across cell faces, so derived shading has no creases.
double fade(double t) { return t * t * t * (t * (6.0 * t - 15.0) + 10.0); }

/// Gradient (Perlin-type) noise in 3D: at each lattice corner a pseudo-random
/// gradient chosen among the 12 directions to the edges of a cube; the value is
/// the fade-weighted trilinear blend of the corners' linear ramps
/// g · (p − corner). Zero at lattice points, roughly in [−1, 1], mean 0.
double gradient_noise(const dvec3& p, std::uint32_t seed) {
  static constexpr std::array<std::array<signed char, 3>, 12> kGradients{{{1, 1, 0},
                                                                          {-1, 1, 0},
                                                                          {1, -1, 0},
                                                                          {-1, -1, 0},
                                                                          {1, 0, 1},
                                                                          {-1, 0, 1},
                                                                          {1, 0, -1},
                                                                          {-1, 0, -1},
                                                                          {0, 1, 1},
                                                                          {0, -1, 1},
                                                                          {0, 1, -1},
                                                                          {0, -1, -1}}};
  const dvec3 cell = glm::floor(p);
  const dvec3 f = p - cell;
  const int x0 = int(cell.x), y0 = int(cell.y), z0 = int(cell.z);
  auto ramp = [&](int dx, int dy, int dz) {
    const auto& g = kGradients[hash_cell(x0 + dx, y0 + dy, z0 + dz, seed) % 12u];
    return double(g[0]) * (f.x - dx) + double(g[1]) * (f.y - dy) + double(g[2]) * (f.z - dz);
  };
  const double u = fade(f.x), v = fade(f.y), w = fade(f.z);
  auto lerp = [](double a, double b, double t) { return a + t * (b - a); };
  const double x00 = lerp(ramp(0, 0, 0), ramp(1, 0, 0), u), x10 = lerp(ramp(0, 1, 0), ramp(1, 1, 0), u);
  const double x01 = lerp(ramp(0, 0, 1), ramp(1, 0, 1), u), x11 = lerp(ramp(0, 1, 1), ramp(1, 1, 1), u);
  return lerp(lerp(x00, x10, v), lerp(x01, x11, v), w);
}

/// Fractional Brownian motion: Σ_k gain^k · noise(2^k · frequency · p), divided
/// by Σ_k gain^k so the result stays roughly in [−1, 1]. Each octave has its own
/// seed and offset so lattice points of different octaves do not line up.
double fbm(const dvec3& p, double frequency, int octaves, std::uint32_t seed, double gain = 0.5) {
  double sum = 0.0, norm = 0.0, amplitude = 1.0;
  for (int k = 0; k < octaves; ++k) {
    const dvec3 offset(17.13 * k, 31.71 * k, 7.37 * k);
    sum += amplitude * gradient_noise(p * frequency + offset, field_seed(seed, std::uint32_t(k)));
    norm += amplitude;
    amplitude *= gain;
    frequency *= 2.0;
  }
  return sum / norm;
}

double smoothstep(double edge0, double edge1, double x) {
  const double t = std::clamp((x - edge0) / (edge1 - edge0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

dvec3 mix(const dvec3& a, const dvec3& b, double t) { return a + (b - a) * t; }

/// Point i of the n-point Fibonacci lattice on the unit sphere: equal areas
/// (z evenly spaced), longitudes turning by the golden angle.
dvec3 fibonacci_point(int i, int n) {
  const double golden_angle = kPi * (3.0 - std::sqrt(5.0));
  const double z = 1.0 - (2.0 * i + 1.0) / n;
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  const double phi = golden_angle * i;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

/// The q-quantile of a field over the unit sphere, estimated from 16384 points
/// of a Fibonacci lattice (equal-area, so the quantile is an area fraction).
/// Independent of the map size, so a seed gives the same planet at any size.
template <typename Field>
double sphere_quantile(const Field& field, double q) {
  constexpr int kPoints = 16384;
  std::vector<double> values(kPoints);
  for (int i = 0; i < kPoints; ++i) values[std::size_t(i)] = field(fibonacci_point(i, kPoints));
  const auto k = std::size_t(std::clamp(q, 0.0, 1.0) * (kPoints - 1));
  std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(k), values.end());
  return values[k];
}

double latitude_deg(const dvec3& p) { return std::asin(std::clamp(p.z, -1.0, 1.0)) / kDeg; }

// ------------------------------------------------------------------ generators

/// A generator: the colour at a point of the unit sphere (body frame).
class Generator {
 public:
  virtual ~Generator() = default;
  virtual dvec3 albedo(const dvec3& p) const = 0;
};

class EarthGenerator final : public Generator {
 public:
  explicit EarthGenerator(std::uint32_t seed)
      : continents_(field_seed(seed, 1)),
        warp_(field_seed(seed, 2)),
        moisture_(field_seed(seed, 3)),
        ice_(field_seed(seed, 4)),
        detail_(field_seed(seed, 5)) {
    // Sea level: the elevation below which 70 % of the sphere lies (Earth: 71 % ocean).
    sea_level_ = sphere_quantile([this](const dvec3& p) { return elevation(p); }, 0.70);
  }

  dvec3 albedo(const dvec3& p) const override {
    const double e = elevation(p) - sea_level_;  // > 0 on land
    const double lat = latitude_deg(p), abs_lat = std::abs(lat);
    const double detail = fbm(p, 24.0, 3, detail_);

    // Ocean: dark blue (mean reflectance ~0.06), lighter over the continental shelf.
    const dvec3 deep(0.025, 0.055, 0.11), shelf(0.045, 0.095, 0.135);
    const dvec3 ocean = mix(deep, shelf, smoothstep(-0.05, 0.0, e));

    // Land cover from latitude (climate belts) and a moisture field.
    const double moisture = fbm(p, 2.5, 5, moisture_) + 0.1 * detail;
    const dvec3 rain_forest(0.03, 0.065, 0.02), temperate(0.07, 0.11, 0.04), grass(0.14, 0.16, 0.07);
    const dvec3 desert(0.42, 0.32, 0.19), boreal(0.05, 0.075, 0.04), tundra(0.16, 0.15, 0.12);
    const dvec3 rock(0.19, 0.17, 0.15), snow(0.75, 0.76, 0.8);
    dvec3 land = mix(rain_forest, temperate, smoothstep(12.0, 25.0, abs_lat));
    land = mix(land, grass, smoothstep(0.0, 0.25, -moisture) * 0.8);
    land = mix(land, boreal, smoothstep(45.0, 55.0, abs_lat));
    land = mix(land, tundra, smoothstep(58.0, 66.0, abs_lat + 3.0 * detail));
    // Subtropical deserts (Hadley-cell descent near 25°), where it is also dry.
    const double aridity = std::exp(-std::pow((abs_lat - 24.0) / 11.0, 2.0)) - 1.8 * moisture;
    land = mix(land, desert, smoothstep(0.45, 0.75, aridity));
    // High ground: bare rock, then snow above a snow line that falls toward the poles.
    const double snow_line = 0.32 - 0.12 * smoothstep(30.0, 70.0, abs_lat);
    land = mix(land, rock, smoothstep(0.16, 0.24, e + 0.03 * detail));
    land = mix(land, snow, smoothstep(snow_line - 0.02, snow_line + 0.02, e + 0.03 * detail));
    land *= 0.9 + 0.2 * (0.5 + 0.5 * detail);

    dvec3 colour = e > 0.0 ? land : ocean;

    // Polar ice over land and sea; the Antarctic reaches further from the pole.
    const double ice_edge = (lat > 0.0 ? 73.0 : 67.0) + 16.0 * fbm(p, 3.0, 5, ice_);
    colour = mix(colour, dvec3(0.70, 0.72, 0.76), smoothstep(ice_edge - 1.5, ice_edge + 1.5, abs_lat));
    return colour;
  }

 private:
  /// Continents: domain-warped fBm (the warp bends the blobs of plain fBm into
  /// elongated, ragged continents).
  double elevation(const dvec3& p) const {
    const dvec3 w(fbm(p, 1.5, 3, warp_), fbm(p + dvec3(5.2, 1.3, 2.8), 1.5, 3, warp_),
                  fbm(p + dvec3(1.7, 9.2, 4.1), 1.5, 3, warp_));
    return fbm(p + 0.45 * w, 1.3, 7, continents_);
  }

  std::uint32_t continents_, warp_, moisture_, ice_, detail_;
  double sea_level_ = 0.0;
};

class MoonGenerator final : public Generator {
 public:
  explicit MoonGenerator(std::uint32_t seed)
      : maria_(field_seed(seed, 11)), detail_(field_seed(seed, 12)), craters_(field_seed(seed, 13)) {
    // Maria cover ~17 % of the surface (the Moon: 16 %), mostly on the near side.
    maria_level_ = sphere_quantile([this](const dvec3& p) { return maria_field(p); }, 0.83);
  }

  dvec3 albedo(const dvec3& p) const override {
    const double detail = fbm(p, 10.0, 4, detail_);
    const double highland = 0.16 + 0.03 * detail;
    const double mare = 0.075 + 0.01 * detail;
    double grey = highland + (mare - highland) * smoothstep(-0.02, 0.02, maria_field(p) - maria_level_);
    grey *= crater_factor(p);
    // A faint warm tint (lunar soil reflects more in the red).
    return dvec3(1.06, 1.0, 0.92) * grey;
  }

 private:
  double maria_field(const dvec3& p) const { return fbm(p, 1.2, 4, maria_) + 0.3 * p.x; }

  /// Craters at four scales. Space is cut into cubic cells of size c; a cell
  /// holds at most one crater, whose centre lies in the cell and, to be on the
  /// surface, within c/4 of the unit sphere; it is projected onto the sphere.
  /// The crater's radius is ≤ c/4 and its ejecta reach 1.8 radii, so a point
  /// needs only its own cell and the 26 around it. Profile in x = distance/radius:
  /// darker floor (x < 0.8), bright rim (x ≈ 0.95), ejecta fading to x = 1.8;
  /// fresher craters (random) have stronger contrast. Returns a factor on the albedo.
  double crater_factor(const dvec3& p) const {
    double factor = 1.0;
    constexpr std::array<double, 4> kCellSizes{0.24, 0.12, 0.06, 0.03};
    for (std::size_t level = 0; level < kCellSizes.size(); ++level) {
      const double c = kCellSizes[level];
      const std::uint32_t seed = field_seed(craters_, std::uint32_t(level));
      const dvec3 base = glm::floor(p / c);
      for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int cx = int(base.x) + dx, cy = int(base.y) + dy, cz = int(base.z) + dz;
            const std::uint32_t h = hash_cell(cx, cy, cz, seed);
            if (uniform(h, 0) > 0.7) continue;  // empty cell
            const dvec3 centre = (dvec3(cx, cy, cz) + dvec3(uniform(h, 1), uniform(h, 2), uniform(h, 3))) * c;
            const double r = glm::length(centre);
            if (std::abs(r - 1.0) > 0.25 * c) continue;  // not on the surface
            const double radius = c * (0.08 + 0.17 * uniform(h, 4));
            const double x = glm::length(p - centre / r) / radius;
            if (x >= 1.8) continue;
            const double fresh = 0.25 + 0.75 * uniform(h, 5);
            const double floor_dark = 1.0 - 0.18 * fresh * (1.0 - smoothstep(0.6, 0.85, x));
            const double rim = 0.35 * fresh * std::exp(-std::pow((x - 0.95) / 0.1, 2.0));
            const double ejecta = x > 1.0 ? 0.12 * fresh * std::pow((1.8 - x) / 0.8, 2.0) : 0.0;
            factor *= floor_dark + rim + ejecta;
          }
    }
    return factor;
  }

  std::uint32_t maria_, detail_, craters_;
  double maria_level_ = 0.0;
};

class MarsGenerator final : public Generator {
 public:
  explicit MarsGenerator(std::uint32_t seed)
      : dark_(field_seed(seed, 21)),
        bright_(field_seed(seed, 22)),
        detail_(field_seed(seed, 23)),
        caps_(field_seed(seed, 24)) {
    dark_level_ = sphere_quantile([this](const dvec3& p) { return dark_field(p); }, 0.75);
    bright_level_ = sphere_quantile([this](const dvec3& p) { return bright_field(p); }, 0.85);
  }

  dvec3 albedo(const dvec3& p) const override {
    const double detail = fbm(p, 12.0, 4, detail_);
    const dvec3 rust(0.35, 0.18, 0.08), dark(0.15, 0.09, 0.055), dusty(0.43, 0.24, 0.11);
    dvec3 colour = rust * (0.92 + 0.16 * (0.5 + 0.5 * detail));
    // Soft edges: Martian albedo features grade into each other over hundreds of km.
    colour = mix(colour, dusty, 0.8 * smoothstep(-0.04, 0.08, bright_field(p) - bright_level_));
    colour = mix(colour, dark * (0.85 + 0.3 * (0.5 + 0.5 * detail)),
                 smoothstep(-0.07, 0.07, dark_field(p) - dark_level_ + 0.04 * detail));
    // Residual polar caps (the northern one larger, as on Mars).
    const double lat = latitude_deg(p);
    const double cap_edge = (lat > 0.0 ? 81.0 : 84.0) + 2.5 * fbm(p, 8.0, 3, caps_);
    return mix(colour, dvec3(0.75, 0.72, 0.68), smoothstep(cap_edge - 0.8, cap_edge + 0.8, std::abs(lat)));
  }

 private:
  /// Dark albedo features lie mostly in a band of southern low latitudes.
  double dark_field(const dvec3& p) const {
    const double lat = latitude_deg(p);
    return fbm(p, 1.8, 5, dark_) + 0.2 * std::exp(-std::pow((lat + 12.0) / 22.0, 2.0));
  }
  double bright_field(const dvec3& p) const { return fbm(p, 1.4, 4, bright_); }

  std::uint32_t dark_, bright_, detail_, caps_;
  double dark_level_ = 0.0, bright_level_ = 0.0;
};

class CheckerGenerator final : public Generator {
 public:
  dvec3 albedo(const dvec3& p) const override {
    const double lon = std::atan2(p.y, p.x) / kDeg;  // (−180, 180]
    const double lat = latitude_deg(p);
    const int column = std::clamp(int(std::floor((lon + 180.0) / 30.0)), 0, 11);
    const int row = std::clamp(int(std::floor((90.0 - lat) / 30.0)), 0, 5);
    return dvec3((column + row) % 2 == 0 ? 0.8 : 0.2);
  }
};

std::unique_ptr<Generator> make_generator(const std::string& name, std::uint32_t seed) {
  if (name == "earth") return std::make_unique<EarthGenerator>(seed);
  if (name == "moon") return std::make_unique<MoonGenerator>(seed);
  if (name == "mars") return std::make_unique<MarsGenerator>(seed);
  if (name == "checker") return std::make_unique<CheckerGenerator>();
  std::ostringstream s;
  s << "unknown albedo generator \"" << name << "\"; available:";
  for (const auto& g : albedo_generators()) s << ' ' << g;
  throw std::invalid_argument(s.str());
}

float clamp01(double x) { return float(std::clamp(x, 0.0, 1.0)); }

}  // namespace

std::vector<std::string> albedo_generators() { return {"earth", "moon", "mars", "checker"}; }

image::LinearImage generate_albedo_map(const std::string& generator, std::uint32_t seed, int width_px, int height_px) {
  const std::unique_ptr<Generator> g = make_generator(generator, seed);
  if (width_px < 2 || width_px > 16384 || height_px < 2 || height_px > 8192) {
    std::ostringstream s;
    s << "albedo map " << width_px << " x " << height_px << " px: width must be in [2, 16384], height in [2, 8192]";
    throw std::invalid_argument(s.str());
  }
  image::LinearImage out;
  out.width = width_px;
  out.height = height_px;
  out.rgb.assign(std::size_t(width_px) * std::size_t(height_px) * 3, 0.0f);
  // Rows are independent: evaluate them in parallel (the result does not depend on the threads).
  core::parallel_for(std::size_t(height_px), 0, [&](std::size_t row) {
    const double lat = (90.0 - (double(row) + 0.5) * 180.0 / height_px) * kDeg;
    for (int column = 0; column < width_px; ++column) {
      const double lon = (-180.0 + (column + 0.5) * 360.0 / width_px) * kDeg;
      const dvec3 colour = g->albedo(direction_from_latitude_longitude(lat, lon));
      float* px = &out.rgb[(row * std::size_t(width_px) + std::size_t(column)) * 3];
      px[0] = clamp01(colour.r);
      px[1] = clamp01(colour.g);
      px[2] = clamp01(colour.b);
    }
  });
  return out;
}

std::string procedural_albedo_fingerprint(const std::string& generator, std::uint32_t seed) {
  const std::unique_ptr<Generator> g = make_generator(generator, seed);
  constexpr int kPoints = 4096;
  std::vector<double> colours;
  colours.reserve(3 * kPoints);
  for (int i = 0; i < kPoints; ++i) {
    const dvec3 colour = g->albedo(fibonacci_point(i, kPoints));
    colours.insert(colours.end(), {colour.r, colour.g, colour.b});
  }
  return core::sha256_hex(colours.data(), colours.size() * sizeof(double));
}

std::string albedo_key(const AlbedoSource& a) {
  std::ostringstream key;
  switch (a.kind) {
    case AlbedoSource::Kind::constant:
      key << "constant " << a.colour_linear_rgb.r << ' ' << a.colour_linear_rgb.g << ' ' << a.colour_linear_rgb.b;
      break;
    case AlbedoSource::Kind::image: key << "image " << a.image_path.string(); break;
    case AlbedoSource::Kind::procedural:
      key << "procedural " << a.procedural << ' ' << a.seed << ' ' << a.width_px << 'x' << a.height_px;
      break;
  }
  return key.str();
}

image::LinearImage load_albedo_map(const AlbedoSource& source) {
  image::LinearImage out;
  switch (source.kind) {
    case AlbedoSource::Kind::constant:
      out.width = out.height = 1;
      out.rgb = {clamp01(source.colour_linear_rgb.r), clamp01(source.colour_linear_rgb.g),
                 clamp01(source.colour_linear_rgb.b)};
      return out;
    case AlbedoSource::Kind::image:
      out = image::read_image(source.image_path);
      for (float& v : out.rgb) v = std::isfinite(v) ? std::clamp(v, 0.0f, 1.0f) : 0.0f;
      return out;
    case AlbedoSource::Kind::procedural:
      return generate_albedo_map(source.procedural, source.seed, source.width_px, source.height_px);
  }
  throw std::invalid_argument("load_albedo_map: invalid AlbedoSource::Kind");
}

}  // namespace zenith::scene
