#include "render/night/star_visibility.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <unordered_map>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include "astro/scintillation.h"
#include "atmosphere/air_mass.h"
#include "core/units.h"
#include "image/tone_mapping.h"

namespace zenith::render {
namespace {

/// The pass's atmosphere that holds the camera and surrounds the site body
/// (`site`): every ray from the camera that meets no body reads its sky at the
/// camera from the 4D tables' sky half. Null where there is none, and where
/// the sun's pass does not draw that sky (AtmospherePass::sunlit: the sun too
/// far down to show, its sky zeroed): then the sky is at least black only.
const AtmospherePass* sky_at_camera(const FrameInProgress& frame, std::size_t site) {
  for (const AtmospherePass& pass : frame.passes)
    if (pass.gpu && static_cast<std::size_t>(pass.body) == site && pass.distance_m <= pass.gpu->top_radius_m())
      return pass.sunlit ? &pass : nullptr;
  return nullptr;
}

using atmosphere::lut::Interval;
using core::kPi;

/// The angle between unit vectors, well conditioned at small angles.
double angle_between(const glm::dvec3& a, const glm::dvec3& b) {
  return 2.0 * std::asin(std::min(1.0, 0.5 * glm::length(a - b)));
}

}  // namespace

bool colour_weights_non_negative(const std::vector<std::array<double, 3>>& rgb_weights) {
  bool yes = true;
  for (const auto& w : rgb_weights) yes &= w[0] >= 0.0 && w[1] >= 0.0 && w[2] >= 0.0;
  return yes;
}

double largest_code_change(const std::array<double, 3>& background, const std::array<double, 3>& delta,
                           bool may_subtract) {
  double worst = 0.0;
  for (std::size_t c = 0; c < 3; ++c) {
    const double d = std::abs(delta[c]);
    const double lowest = may_subtract ? std::max(background[c] - d, 0.0) : std::max(background[c], 0.0);
    worst = std::max(worst, image::display_code_slope_bound(lowest) * d);
  }
  return worst;
}

std::array<double, 3> darkest_sky(const FrameInProgress& frame, std::size_t site, double exposure,
                                  const std::vector<std::array<double, 3>>& rgb_weights) {
  std::array<double, 3> out{0.0, 0.0, 0.0};
  const AtmospherePass* pass = colour_weights_non_negative(rgb_weights) ? sky_at_camera(frame, site) : nullptr;
  if (!pass) return out;
  const scene::Scene& scene = frame.scene;
  const glm::dvec3 camera_m = scene.camera.position_m, planet_m = scene.bodies.at(site).position_m;
  const glm::dvec3 up = glm::normalize(camera_m - planet_m);
  const double radius = std::max(pass->distance_m, pass->gpu->ground_radius_m());
  const std::vector<double> k =
      pass->gpu->radiance_lower_bound().radiance_per_irradiance(glm::dot(up, frame.sun), radius);
  for (std::size_t i = 0; i < rgb_weights.size() && i < k.size() && i < scene.sun.irradiance_W_m2_nm.size(); ++i)
    for (std::size_t c = 0; c < 3; ++c) out[c] += exposure * rgb_weights[i][c] * scene.sun.irradiance_W_m2_nm[i] * k[i];
  return out;
}

std::optional<double> splat_footprint_radius(const warp::Projection& projection, const glm::dmat3& camera_to_world,
                                             const glm::dvec2& pixel, const glm::dvec3& direction) {
  double largest = 0.0;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      if (dx == 0 && dy == 0) continue;
      const auto ray = projection.ray(pixel.x + dx, pixel.y + dy);
      if (!ray) return std::nullopt;
      largest = std::max(largest, angle_between(glm::normalize(camera_to_world * *ray), direction));
    }
  return 1.05 * largest + 1e-6;
}

namespace {

/// The range of ν = cos θ cos θs + sin θ sin θs cos φ over θ ∈ theta, φ ∈ phi
/// (⊂ [0, π]): for a fixed θ monotonic in cos φ; for a fixed φ R cos(θ − θ*),
/// whose least over an interval is at an end and whose largest is R where θ*
/// lies within it.
Interval nu_over(Interval theta, Interval phi, double sun_theta) {
  const double cs = std::cos(sun_theta), ss = std::sin(sun_theta);
  const auto nu = [&](double t, double p) { return std::cos(t) * cs + std::sin(t) * ss * std::cos(p); };
  Interval out{2.0, -2.0};
  for (double t : {theta.lo, theta.hi})
    for (double p : {phi.lo, phi.hi}) {
      out.lo = std::min(out.lo, nu(t, p));
      out.hi = std::max(out.hi, nu(t, p));
    }
  const double b = ss * std::cos(phi.lo);  // the largest cos φ
  const double peak = std::atan2(b, cs);
  if (peak >= theta.lo && peak <= theta.hi) out.hi = std::max(out.hi, std::hypot(cs, b));
  return {std::max(-1.0, out.lo - 1e-6), std::min(1.0, out.hi + 1e-6)};
}

}  // namespace

SkyBehindStarBound::SkyBehindStarBound(const atmosphere::lut::SkyRadianceLowerBound& floor, const glm::dvec3& camera_m,
                                       const glm::dvec3& planet_centre_m, double ground_radius_m, const glm::dvec3& sun,
                                       bool sky_view, const std::vector<std::array<double, 3>>& rgb_weights,
                                       const std::vector<double>& sun_irradiance, double exposure,
                                       std::vector<std::pair<glm::dvec3, double>> bodies,
                                       std::array<double, 3> whole_sky)
    : camera_m_(camera_m),
      up_(glm::normalize(camera_m - planet_centre_m)),
      sun_(sun),
      sky_view_(sky_view),
      weights_(rgb_weights),
      sun_irradiance_(sun_irradiance),
      exposure_(exposure),
      bodies_(std::move(bodies)),
      whole_sky_(whole_sky) {
  radius_m_ = std::max(glm::length(camera_m - planet_centre_m), ground_radius_m);
  const double ratio = std::min(1.0, ground_radius_m / radius_m_);
  mu_horizon_ = -std::sqrt(std::max(0.0, 1.0 - ratio * ratio));
  theta_horizon_ = kPi - std::asin(ratio);  // SkyViewTable::theta_horizon_rad
  sun_theta_ = std::acos(std::clamp(glm::dot(up_, sun_), -1.0, 1.0));
  slice_ = floor.slice(glm::dot(up_, sun_), radius_m_);
}

bool SkyBehindStarBound::kept(const glm::dvec3& d, double radius_rad) const {
  if (angle_between(d, sun_) < radius_rad + 5.0 * core::kDeg) return true;
  const double lowest_elevation = 0.5 * kPi - std::acos(std::clamp(glm::dot(d, up_), -1.0, 1.0)) - radius_rad;
  if (lowest_elevation < std::asin(mu_horizon_) + 1.0 * core::kDeg) return true;
  for (const auto& [centre, radius] : bodies_) {
    const glm::dvec3 v = centre - camera_m_;
    const double distance = glm::length(v);
    if (distance <= radius) return true;
    if (angle_between(d, v / distance) < std::asin(radius / distance) + radius_rad + 0.5 * core::kDeg) return true;
  }
  return false;
}

std::array<double, 3> SkyBehindStarBound::at(const glm::dvec3& d, double radius_rad) const {
  if (kept(d, radius_rad)) return whole_sky_;
  const double theta = std::acos(std::clamp(glm::dot(d, up_), -1.0, 1.0));
  const Interval thetas{std::max(0.0, theta - radius_rad), std::min(theta_horizon_, theta + radius_rad)};
  // The azimuth from the sun's vertical: all of it near the zenith (there the
  // GPU's φ from ν and μ is ill-conditioned) or with the sun overhead.
  Interval phi{0.0, kPi};
  const glm::dvec3 dh = d - glm::dot(d, up_) * up_, sh = sun_ - glm::dot(sun_, up_) * up_;
  if (thetas.lo > 2.0 * core::kDeg && glm::length(sh) > 1e-3) {
    const double centre = std::acos(std::clamp(glm::dot(dh, sh) / (glm::length(dh) * glm::length(sh)), -1.0, 1.0));
    const double half = std::asin(std::min(1.0, std::sin(radius_rad) / std::sin(theta))) + 1e-4;
    phi = {std::max(0.0, centre - half), std::min(kPi, centre + half)};
  }
  const double gamma = angle_between(d, sun_);
  const Interval nu{std::cos(std::min(kPi, gamma + radius_rad)), std::cos(std::max(0.0, gamma - radius_rad))};
  const std::size_t n = slice_.channels();
  std::vector<double> s(n), v(n);
  slice_.radiance_per_irradiance({std::cos(thetas.hi), std::cos(thetas.lo)}, phi, nu, nu, s.data());
  if (sky_view_) {
    // The sky-view table's texels the cap's pixels interpolate
    // (sky_view_mapping.glsl): x_θ = 1 − √(1 − θ/θh) over 63 spacings, x_φ =
    // sin(φ/2) over 127; each texel a 4D read at its own (θ, φ); A = R P_R(ν
    // of the texel) + multiple, M at the pixel's own Mie phase.
    constexpr double kZenith = 63.0, kAzimuth = 127.0;
    const auto x_theta = [&](double t) { return 1.0 - std::sqrt(std::max(0.0, 1.0 - t / theta_horizon_)); };
    const double j0 = std::clamp(std::floor(x_theta(thetas.lo) * kZenith - 1e-3), 0.0, kZenith);
    const double j1 = std::clamp(std::ceil(x_theta(thetas.hi) * kZenith + 1e-3), 0.0, kZenith);
    const double i0 = std::clamp(std::floor(std::sin(0.5 * phi.lo) * kAzimuth - 1e-3), 0.0, kAzimuth);
    const double i1 = std::clamp(std::ceil(std::sin(0.5 * phi.hi) * kAzimuth + 1e-3), 0.0, kAzimuth);
    const auto texel_theta = [&](double j) {
      return theta_horizon_ * (1.0 - (1.0 - j / kZenith) * (1.0 - j / kZenith));
    };
    const auto texel_phi = [&](double i) {
      return std::acos(std::clamp(1.0 - 2.0 * (i / kAzimuth) * (i / kAzimuth), -1.0, 1.0));
    };
    const Interval texel_thetas{texel_theta(j0), texel_theta(j1)}, texel_phis{texel_phi(i0), texel_phi(i1)};
    slice_.radiance_per_irradiance({std::cos(texel_thetas.hi), std::cos(texel_thetas.lo)}, texel_phis,
                                   nu_over(texel_thetas, texel_phis, sun_theta_), nu, v.data());
    for (std::size_t i = 0; i < n; ++i) s[i] = std::min(s[i], v[i]);
  }
  std::array<double, 3> out = whole_sky_;
  for (std::size_t c = 0; c < 3; ++c) {
    double b = 0.0;
    for (std::size_t i = 0; i < n && i < weights_.size() && i < sun_irradiance_.size(); ++i)
      b += exposure_ * weights_[i][c] * sun_irradiance_[i] * s[i];
    out[c] = std::max(out[c], b);
  }
  return out;
}

bool invisible_change(double background, double delta, bool may_subtract) {
  const double d = std::abs(delta);
  const double lowest = may_subtract ? std::max(background - d, 0.0) : std::max(background, 0.0);
  return image::display_code_slope_bound(lowest) * d < kInvisibleCodeChange;
}

double smallest_pixel_solid_angle_sr(const warp::Projection& projection) {
  double smallest = 0.0;
  for (int j = 0; j <= 32; ++j)
    for (int i = 0; i <= 32; ++i) {
      const double omega = projection.pixel_solid_angle_by_rays_sr((projection.width() - 1) * i / 32.0 + 0.5,
                                                                   (projection.height() - 1) * j / 32.0 + 0.5);
      if (omega > 0.0 && (smallest == 0.0 || omega < smallest)) smallest = omega;
    }
  return 0.5 * smallest;
}

namespace {

/// star_visibility()'s two stages step by step (star_visibility.h gives the
/// argument of each), with what the steps share: the frame's reach and
/// cluster radius, the smallest pixel's solid angle, the light a line of
/// sight keeps per degree of elevation, and, star by star, the stars' places,
/// the sky behind one star and the stars that can be drawn.
class StarTest {
 public:
  StarTest(const FrameInProgress& frame, StarField& field, const StarFrame& sky, const astro::AstroTime& time)
      : frame_(frame),
        field_(field),
        sky_(sky),
        scene_(frame.scene),
        years_from_j2000_(((time.utc().day1 - 2451545.0) + time.utc().day2) / 365.25),
        n_(sky.rgb_weights.size()),
        site_(scene_.sky_clock ? scene_.sky_clock->body : 0),
        planet_(scene_.bodies.at(site_)),
        up_(glm::normalize(sky.camera_m - planet_.position_m)),
        r_(glm::length(sky.camera_m - planet_.position_m)),
        // A pixel gathers the stars whose 2 × 2 splat reaches its centre: within
        // √2 pixel spacings, two pixel angles with the margin. On the catalogue's
        // places the cluster is widened by half for refraction's compression of
        // the sky near the horizon (at most a fifth on Earth) and by 1′ for the
        // aberration's difference across it.
        reach_(2.0 * frame.projection.max_pixel_angle_rad()),
        cluster_radius_(1.5 * reach_ + core::kDeg / 60.0),
        gathered_(field.brightest_cluster_irradiance(cluster_radius_, years_from_j2000_)),
        omega_(smallest_pixel_solid_angle_sr(frame.projection)),
        scale_(sky.exposure / omega_),
        lanes_(std::max<std::size_t>(n_, 8)),
        weights_non_negative_(colour_weights_non_negative(sky.rgb_weights)),
        may_subtract_(!weights_non_negative_) {}

  /// Whether the image has a pixel to bound (else the pass runs).
  bool has_pixels() const { return omega_ > 0.0; }

  // ---- The first stage: every star at once.

  /// The most a star's light can keep through the air the camera is in and
  /// its twinkling, per wavelength: T(r, μ) grows with the elevation and the
  /// twinkling's variance falls with it (X³, capped at 1), so over each degree
  /// [e_k, e_k+1] of apparent elevation T ≤ T(e_k+1) and the factor ≤ its value
  /// at e_k with the largest normal any draw gives; without twinkling T at the
  /// zenith. Without such air, 1 (and the largest factor at the horizon).
  /// Per degree k, by_degree_[k]: T(e_k+1) times the twinkle factor at e_k;
  /// kept_ is their largest.
  void bound_light_kept_by_elevation() {
    const StarAtmosphere* air = nullptr;
    for (const StarAtmosphere& a : sky_.atmospheres)
      if (a.centre_m == planet_.position_m && r_ <= a.top_radius_m) air = &a;
    by_degree_.assign(90 * lanes_, 1.0);
    kept_.assign(lanes_, 0.0);
    const double g = sky_.scintillation ? field_.largest_scintillation_normal(sky_.scintillation_interval) : 0.0;
    const auto factor = [&](double elevation_deg) {
      if (!sky_.scintillation) return 1.0;
      const double variance =
          astro::scintillation_variance(*sky_.scintillation, atmosphere::pickering_air_mass(elevation_deg),
                                        sky_.observer_altitude_m, sky_.ground_refractivity);
      // The pass reads s from its table (TwinkleSigmaTable): within ε of the
      // formula's, so its factor within exp(ε (|g| + s + ε)) of this one's (s ≤ √ln 2).
      const double e = sky_.twinkle_sigma ? sky_.twinkle_sigma->error_bound() : 0.0;
      return astro::scintillation_factor(variance, g) * std::exp(e * (std::abs(g) + std::sqrt(std::log(2.0)) + e));
    };
    glm::dvec3 level = glm::cross(up_, glm::dvec3(1, 0, 0));
    if (glm::length(level) < 0.1) level = glm::cross(up_, glm::dvec3(0, 1, 0));
    level = glm::normalize(level);
    for (int e = 0; e < 90; ++e) {
      double* t = &by_degree_[static_cast<std::size_t>(e) * lanes_];
      const double above = (e + 1) * core::kDeg;
      if (air) star_transmittance(*air, sky_.camera_m, std::cos(above) * level + std::sin(above) * up_, t);
      const double f = factor(e);
      for (std::size_t i = 0; i < lanes_; ++i) kept_[i] = std::max(kept_[i], t[i] * f);
      for (std::size_t i = 0; i < lanes_; ++i) t[i] *= f;
    }
  }

  /// The first stage's answer into `out`: the sky's floor B from the tables
  /// (where it applies), the most the brightest cluster can add to one pixel
  /// through the air and against a black sky, whether that could show, and
  /// the code change it could make.
  void bound_every_star_at_once(StarVisibility& out) {
    pass_ = weights_non_negative_ ? sky_at_camera(frame_, site_) : nullptr;
    out.sky_floor = darkest_sky(frame_, site_, sky_.exposure, sky_.rgb_weights);
    for (std::size_t c = 0; c < 3; ++c)
      for (std::size_t i = 0; i < n_ && i < gathered_.size(); ++i)
        out.sky_peak[c] += scale_ * std::abs(sky_.rgb_weights[i][c]) * gathered_[i] * kept_[i];
    double weight = 0.0;
    for (const auto& w : sky_.rgb_weights) weight += std::max({std::abs(w[0]), std::abs(w[1]), std::abs(w[2])});
    const double twinkle =
        sky_.scintillation ? astro::scintillation_factor(1.0, astro::kLargestScintillationNormal) : 1.0;
    out.black_sky_peak = sky_.exposure * field_.brightest_irradiance() * weight * twinkle / omega_;
    out.could_show = false;
    for (std::size_t c = 0; c < 3; ++c)
      out.could_show = out.could_show || !invisible_change(out.sky_floor[c], out.sky_peak[c], may_subtract_);
    out.code_change = largest_code_change(out.sky_floor, out.sky_peak, may_subtract_);
    sky_floor_ = out.sky_floor;
  }

  // ---- The second stage: the brightest m stars one by one, the rest together.

  /// The stars' places (`enu`, filled by the caller: StarField::directions_enu)
  /// and the sky behind one star (the second stage's B_s) where the tables give it.
  void start_star_by_star(const std::vector<glm::dvec3>& enu) {
    enu_ = &enu;
    if (!pass_) return;
    std::vector<std::pair<glm::dvec3, double>> bodies;
    for (std::size_t b = 0; b < scene_.bodies.size(); ++b)
      if (b != site_) bodies.emplace_back(scene_.bodies[b].position_m, scene_.bodies[b].radius_m);
    behind_.emplace(pass_->gpu->radiance_lower_bound(), sky_.camera_m, planet_.position_m,
                    pass_->gpu->ground_radius_m(), frame_.sun, pass_->sky_view, sky_.rgb_weights,
                    scene_.sun.irradiance_W_m2_nm, sky_.exposure, std::move(bodies), sky_floor_);
  }

  /// At night the stars show, and the ladder below would say so only after a
  /// pass over every drawable star per rung and the sky over the rest's cubes
  /// (~25 ms a frame on this project's VM). The brightest kFirstStarsTested
  /// stars in the image alone answer first: a star whose own splat, against the
  /// sky behind it, could move a code half a step makes the whole test answer
  /// "could show" as well — every rung keeps it among the bright stars placed
  /// below, whose `delta` only adds its neighbours and the rest to its own
  /// light, or among the rest, whose bound for it holds its own light against
  /// a sky no brighter than the one behind its splat; the code change grows
  /// with what is added — so the pass runs now, on the same decision, for the
  /// price of placing a few stars. Those are the first to land in the image
  /// among the catalogue's kFirstStarsScanned brightest (one dot product
  /// rejects each of the others): a narrow view holds few of the very
  /// brightest (a 79° ground view none of the 16 at 22:00 on the winter
  /// solstice, where the ladder took 3.7 ms of its frame).
  /// True (and `out` says so) when one of them could show.
  bool a_bright_star_could_show_alone(StarVisibility& out) const {
    const std::vector<glm::dvec3>& enu = *enu_;
    std::vector<double> scratch_a(n_), scratch_b(n_);
    std::size_t placed = 0;
    for (std::size_t i = 0; i < std::min(kFirstStarsScanned, enu.size()) && placed < kFirstStarsTested; ++i) {
      const auto p = place_star(field_, i, enu[i], sky_, scratch_a, scratch_b);
      if (!p) continue;
      ++placed;
      const double change = splat_change(*p, {std::abs(p->rgb[0]), std::abs(p->rgb[1]), std::abs(p->rgb[2])});
      if (change >= kInvisibleCodeChange) {
        out.stars_tested = i + 1;
        out.code_change = change;
        return true;
      }
    }
    return false;
  }

  /// The rest: per star j after the m-th that can be drawn (above the ground,
  /// within the view's cone), the stars after the m-th within twice the
  /// cluster's radius of it (StarField::neighbourhood_irradiance: a pixel that
  /// gathers j gathers no more of them) through the most a line of sight
  /// within that reach (and refraction's lift, < 1°) of j's elevation keeps.
  /// Here: that most per degree (near_kept_), and the drawable stars with
  /// their elevation's degree.
  void list_drawable_stars() {
    const double reach_deg = 2.0 * cluster_radius_ / core::kDeg + 1.0;
    const int window = static_cast<int>(std::ceil(reach_deg)) + 1;
    near_kept_.assign(90 * lanes_, 0.0);  // per degree, the largest of by_degree_ within the window
    for (int k = 0; k < 90; ++k)
      for (int e = std::max(0, k - window); e <= std::min(89, k + window); ++e)
        for (std::size_t i = 0; i < lanes_; ++i)
          near_kept_[static_cast<std::size_t>(k) * lanes_ + i] =
              std::max(near_kept_[static_cast<std::size_t>(k) * lanes_ + i],
                       by_degree_[static_cast<std::size_t>(e) * lanes_ + i]);
    const std::vector<glm::dvec3>& enu = *enu_;
    drawable_.clear();
    for (std::size_t j = 0; j < enu.size(); ++j) {
      const glm::dvec3& v = enu[j];
      if (v.z < sky_.lowest_sin_altitude) continue;
      if (glm::dot(v.x * sky_.east + v.y * sky_.north + v.z * sky_.up, sky_.view_axis) < sky_.view_cos_limit) continue;
      drawable_.emplace_back(j, degree_of(v));
    }
  }

  /// The ladder: the rest after the brightest m = 16, 64, … stars until the
  /// rest alone cannot show (or, at kMostStarsTested, can show only where its
  /// own sky allows). The rung it stopped at and what the rest alone can do
  /// there; nothing when too many stars could matter (`out` says so: the pass runs).
  struct Rung {
    std::size_t m = 0;
    double rest_change = 0.0;  ///< the most the rest alone can move a code
  };
  std::optional<Rung> climb_the_ladder(StarVisibility& out) {
    Rung rung;
    for (std::size_t trial = kFirstStarsTested;; trial *= 4) {
      rung.m = std::min(trial, field_.size());
      rung.rest_change = largest_code_change(sky_floor_, rest_of(rung.m), may_subtract_);
      if (rung.rest_change <= 0.25 * kInvisibleCodeChange) return rung;
      if (rung.m < std::min(field_.size(), kMostStarsTested)) continue;
      if (rung.rest_change < kInvisibleCodeChange) return rung;  // the bright stars get what the rest leaves
      rung.rest_change = rest_against_the_sky_behind_it(rung.m);
      if (rung.rest_change < kInvisibleCodeChange) return rung;
      out.stars_tested = rung.m;  // too many stars could matter: the pass runs
      out.code_change = rung.rest_change;
      return std::nullopt;
    }
  }

  /// The brightest m stars placed, each with the rest's stars within twice the
  /// cluster's radius of it (their sum through the line of sight near its
  /// elevation) and its placed neighbours whose splats can share a pixel with
  /// its own: true (and `out` says so) when one could show; else `out` holds
  /// the largest code change of all.
  bool a_bright_star_could_show_with_its_neighbours(const Rung& rung, StarVisibility& out) const {
    const std::vector<glm::dvec3>& enu = *enu_;
    const std::size_t m = rung.m;
    struct Bright {
      PlacedStar star;
      std::array<double, 3> rest{};
    };
    std::vector<Bright> placed;
    std::vector<double> scratch_a(n_), scratch_b(n_);
    const std::vector<double>& near = field_.neighbourhood_irradiance(cluster_radius_, years_from_j2000_, m);
    for (std::size_t i = 0; i < m && i < enu.size(); ++i)
      if (auto p = place_star(field_, i, enu[i], sky_, scratch_a, scratch_b)) {
        Bright b{*p, {}};
        const int degree = degree_of(enu[i]);
        for (std::size_t c = 0; c < 3; ++c)
          for (std::size_t k = 0; k < n_; ++k)
            b.rest[c] += scale_ * std::abs(sky_.rgb_weights[k][c]) * near[i * n_ + k] *
                         near_kept_[static_cast<std::size_t>(degree) * lanes_ + k];
        placed.push_back(b);
      }
    out.stars_placed = placed.size();

    // Neighbours whose splats can share a pixel: within 2 pixels in x and y, in cells of 2 pixels.
    const auto cell = [](double x, double y) {
      return (static_cast<std::int64_t>(std::floor(0.5 * x)) << 32) ^
             static_cast<std::int64_t>(static_cast<std::uint32_t>(static_cast<std::int32_t>(std::floor(0.5 * y))));
    };
    std::unordered_map<std::int64_t, std::vector<std::size_t>> cells;
    for (std::size_t s = 0; s < placed.size(); ++s)
      cells[cell(placed[s].star.pixel.x, placed[s].star.pixel.y)].push_back(s);
    double largest = rung.rest_change;
    for (const Bright& b : placed) {
      const PlacedStar& s = b.star;
      std::array<double, 3> delta{};
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const auto it = cells.find(cell(s.pixel.x + 2.0 * dx, s.pixel.y + 2.0 * dy));
          if (it == cells.end()) continue;
          for (std::size_t o : it->second)
            if (std::abs(placed[o].star.pixel.x - s.pixel.x) <= 2.0 &&
                std::abs(placed[o].star.pixel.y - s.pixel.y) <= 2.0)
              for (std::size_t c = 0; c < 3; ++c) delta[c] += std::abs(placed[o].star.rgb[c]);
        }
      for (std::size_t c = 0; c < 3; ++c) delta[c] = delta[c] * (1.0 + 1e-3) + b.rest[c];
      const double change = splat_change(s, delta);
      largest = std::max(largest, change);
      if (change >= kInvisibleCodeChange) {
        out.code_change = change;
        return true;
      }
    }
    out.code_change = largest;
    return false;
  }

 private:
  /// The degree of elevation [0, 89] a geometric direction (east, north, up) lies in.
  static int degree_of(const glm::dvec3& enu) {
    return std::clamp(static_cast<int>(std::floor(std::asin(std::clamp(enu.z, -1.0, 1.0)) / core::kDeg)), 0, 89);
  }

  /// The most |delta| on a placed star's splat can move a code: against the
  /// darkest sky, and where that could show, against the sky behind the star.
  double splat_change(const PlacedStar& star, const std::array<double, 3>& delta) const {
    double change = largest_code_change(sky_floor_, delta, may_subtract_);
    if (change >= kInvisibleCodeChange && behind_) {
      const auto rho = splat_footprint_radius(frame_.projection, frame_.camera_to_world, star.pixel, star.direction);
      if (rho) change = largest_code_change(behind_->at(star.direction, *rho), delta, may_subtract_);
    }
    return change;
  }

  /// Per drawable star j after the m-th: its neighbourhood's most on one pixel (per channel).
  template <class Visit>
  void for_each_rest_star(std::size_t m, Visit&& visit) const {
    const std::vector<double>& near = field_.neighbourhood_irradiance(cluster_radius_, years_from_j2000_, m);
    const auto first = std::lower_bound(drawable_.begin(), drawable_.end(), std::pair<std::size_t, int>{m, -1});
    for (auto it = first; it != drawable_.end(); ++it) {
      const std::size_t j = it->first;
      const double* k = &near_kept_[static_cast<std::size_t>(it->second) * lanes_];
      const double* e = &near[j * n_];
      std::array<double, 3> f{};
      for (std::size_t c = 0; c < 3; ++c) {
        for (std::size_t i = 0; i < n_; ++i) f[c] += std::abs(sky_.rgb_weights[i][c]) * e[i] * k[i];
        f[c] *= scale_;
      }
      visit(j, f);
    }
  }

  /// The most the rest after the m-th star puts on one pixel, per channel.
  std::array<double, 3> rest_of(std::size_t m) const {
    std::array<double, 3> rest{};
    for_each_rest_star(m, [&](std::size_t, const std::array<double, 3>& f) {
      for (std::size_t c = 0; c < 3; ++c) rest[c] = std::max(rest[c], f[c]);
    });
    return rest;
  }

  /// Pixels only the rest touches, against the sky behind each star of the
  /// rest whose neighbourhood could show on the darkest sky: its pixels lie
  /// within `reach` of its apparent direction, which refraction lifts by
  /// under 1° from its geometric one, which lies in a cube of side h of the
  /// (east, north, up) grid: within δ = √3 h / 2 of the cube's centre c, so
  /// within asin(δ / (1 − δ)) of c's direction. The sky over that cap, once
  /// per cube (or, with colour weights that may subtract, the darkest sky's);
  /// per channel the code's slope there. The most the rest can move a code.
  double rest_against_the_sky_behind_it(std::size_t m) const {
    constexpr double kCube = 0.06;
    const double delta = 0.5 * std::sqrt(3.0) * kCube;
    const double cap = std::asin(delta / (1.0 - delta)) + 1.0 * core::kDeg + reach_;
    std::unordered_map<std::int64_t, std::pair<std::array<double, 3>, std::array<double, 3>>> cells;
    const auto slopes = [](const std::array<double, 3>& background) {
      return std::array<double, 3>{image::display_code_slope_bound(background[0]),
                                   image::display_code_slope_bound(background[1]),
                                   image::display_code_slope_bound(background[2])};
    };
    const auto change_at = [&](const std::array<double, 3>& slope, const std::array<double, 3>& background,
                               const std::array<double, 3>& f) {
      if (may_subtract_) return largest_code_change(background, f, true);
      return std::max({slope[0] * f[0], slope[1] * f[1], slope[2] * f[2]});
    };
    const std::vector<glm::dvec3>& enu = *enu_;
    const std::array<double, 3> darkest = slopes(sky_floor_);
    double worst = 0.0;
    for_each_rest_star(m, [&](std::size_t j, const std::array<double, 3>& f) {
      double c = change_at(darkest, sky_floor_, f);
      if (c >= kInvisibleCodeChange && behind_) {
        const glm::dvec3& v = enu[j];
        const std::int64_t x = static_cast<std::int64_t>(std::floor(v.x / kCube)),
                           y = static_cast<std::int64_t>(std::floor(v.y / kCube)),
                           z = static_cast<std::int64_t>(std::floor(v.z / kCube));
        const std::int64_t key = ((x + 64) * 128 + (y + 64)) * 128 + (z + 64);
        auto it = cells.find(key);
        if (it == cells.end()) {
          const glm::dvec3 centre =
              (glm::dvec3(static_cast<double>(x), static_cast<double>(y), static_cast<double>(z)) + 0.5) * kCube;
          const glm::dvec3 d = glm::normalize(centre.x * sky_.east + centre.y * sky_.north + centre.z * sky_.up);
          const std::array<double, 3> floor = behind_->at(d, cap);
          it = cells.emplace(key, std::pair{floor, slopes(floor)}).first;
        }
        c = change_at(it->second.second, it->second.first, f);
      }
      worst = std::max(worst, c);
    });
    return worst;
  }

  const FrameInProgress& frame_;
  StarField& field_;
  const StarFrame& sky_;
  const scene::Scene& scene_;
  double years_from_j2000_;
  std::size_t n_;     ///< wavelengths
  std::size_t site_;  ///< the body the sky clock stands on
  const scene::Body& planet_;
  glm::dvec3 up_;
  double r_;                             ///< the camera's distance from the site body's centre
  double reach_;                         ///< two pixel angles
  double cluster_radius_;                ///< the radius of sky one pixel gathers stars from
  const std::vector<double>& gathered_;  ///< the brightest cluster's irradiance per wavelength
  double omega_;                         ///< half the smallest pixel solid angle
  double scale_;                         ///< exposure / Ω
  std::size_t lanes_;                    ///< wavelengths, at least 8 (star_transmittance's width)
  bool weights_non_negative_, may_subtract_;
  std::vector<double> by_degree_, kept_, near_kept_;
  const AtmospherePass* pass_ = nullptr;  ///< the sky at the camera, where the tables give its floor
  std::array<double, 3> sky_floor_{};
  const std::vector<glm::dvec3>* enu_ = nullptr;
  std::optional<SkyBehindStarBound> behind_;
  std::vector<std::pair<std::size_t, int>> drawable_;  ///< the stars that can be drawn, and their degree
};

}  // namespace

StarVisibility star_visibility(const FrameInProgress& frame, StarField& field, const StarFrame& sky,
                               const astro::AstroTime& time, const astro::Site& clock_site,
                               std::vector<glm::dvec3>& directions_enu, bool star_by_star) {
  StarVisibility out;
  directions_enu.clear();
  StarTest test(frame, field, sky, time);
  if (!test.has_pixels()) return out;  // no pixel to bound: the pass runs

  test.bound_light_kept_by_elevation();
  test.bound_every_star_at_once(out);
  if (!out.could_show || !star_by_star) return out;

  field.directions_enu(time, clock_site, directions_enu);
  test.start_star_by_star(directions_enu);
  if (test.a_bright_star_could_show_alone(out)) return out;  // the pass runs
  test.list_drawable_stars();
  const std::optional<StarTest::Rung> rung = test.climb_the_ladder(out);
  if (!rung) return out;  // too many stars could matter: the pass runs
  out.stars_tested = rung->m;
  if (test.a_bright_star_could_show_with_its_neighbours(*rung, out)) return out;  // the pass runs
  out.could_show = false;
  return out;
}

}  // namespace zenith::render
