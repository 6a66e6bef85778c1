#include "render/night/star_transmittance.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "atmosphere/lut/parameterization.h"

namespace zenith::render {

void star_transmittance(const StarAtmosphere& a, const glm::dvec3& camera_m, const glm::dvec3& d, double* out) {
  const atmosphere::lut::LookupTables& t = *a.transmittance;
  const std::size_t n = t.channels;
  const glm::dvec3 p = camera_m - a.centre_m;
  const double r = glm::length(p);
  const double mu = glm::dot(p, d) / r;
  const double b = r * mu;                               // p·d
  const double closest2 = std::max(0.0, r * r - b * b);  // squared distance of the line from the centre
  std::fill(out, out + n, 1.0);
  if (b < 0.0 && closest2 < a.ground_radius_m * a.ground_radius_m) {  // the ground hides it
    std::fill(out, out + n, 0.0);
    return;
  }
  double r_at = r, mu_at = mu;
  if (r > a.top_radius_m) {
    if (b >= 0.0 || closest2 >= a.top_radius_m * a.top_radius_m) return;  // misses the shell
    // Where it enters the shell: the same line from there.
    const double t_in = -b - std::sqrt(a.top_radius_m * a.top_radius_m - closest2);
    r_at = a.top_radius_m;
    mu_at = std::clamp((b + t_in) / a.top_radius_m, -1.0, 1.0);
  }
  const atmosphere::lut::TransmittanceUV uv = atmosphere::lut::transmittance_uv(
      t.geometry, t.sizes, std::clamp(r_at, a.ground_radius_m, a.top_radius_m), mu_at);
  t.transmittance.sample(uv.u_mu, uv.v_r, out);
  for (std::size_t c = 0; c < n; ++c) out[c] = std::clamp(out[c], 0.0, 1.0);
}

CameraTransmittance::CameraTransmittance(const StarAtmosphere& a, const glm::dvec3& camera_m)
    : geometry_(a.transmittance->geometry),
      p_(camera_m - a.centre_m),
      ground_(a.ground_radius_m),
      top_(a.top_radius_m),
      r_(glm::length(camera_m - a.centre_m)) {
  const atmosphere::lut::LookupTables& t = *a.transmittance;
  const atmosphere::lut::ShellGeometry& g = geometry_;
  // The radius every ray is read at (star_transmittance), its row weight and the ends of its u_μ.
  r_at_ = r_ > a.top_radius_m ? a.top_radius_m : std::clamp(r_, a.ground_radius_m, a.top_radius_m);
  const atmosphere::lut::TransmittanceUV uv = atmosphere::lut::transmittance_uv(g, t.sizes, r_at_, 1.0);
  d_min_ = g.top_radius_m - r_at_;
  d_max_ = g.horizon_distance_m(r_at_) + g.horizon_distance_at_top_m();
  width_ = t.transmittance.width;
  channels_ = t.channels;
  // GL_LINEAR with GL_CLAMP_TO_EDGE across the rows (atmosphere/lut/table.h).
  const double y = uv.v_r * double(t.transmittance.height) - 0.5, fy = std::floor(y);
  const auto last = static_cast<std::ptrdiff_t>(t.transmittance.height) - 1;
  const auto y0 = static_cast<std::size_t>(std::clamp(static_cast<std::ptrdiff_t>(fy), std::ptrdiff_t{0}, last));
  const auto y1 = static_cast<std::size_t>(std::clamp(static_cast<std::ptrdiff_t>(fy) + 1, std::ptrdiff_t{0}, last));
  const double wy = y - fy;
  row_.resize(width_ * channels_);
  for (std::size_t x = 0; x < width_; ++x)
    for (std::size_t c = 0; c < channels_; ++c)
      row_[x * channels_ + c] =
          (1.0 - wy) * double(t.transmittance.texel(x, y0)[c]) + wy * double(t.transmittance.texel(x, y1)[c]);
}

void CameraTransmittance::operator()(const glm::dvec3& d, double* out) const {
  const double mu = glm::dot(p_, d) / r_;
  const double b = r_ * mu;                                // p·d
  const double closest2 = std::max(0.0, r_ * r_ - b * b);  // squared distance of the line from the centre
  std::fill(out, out + channels_, 1.0);
  if (b < 0.0 && closest2 < ground_ * ground_) {  // the ground hides it
    std::fill(out, out + channels_, 0.0);
    return;
  }
  double mu_at = mu;
  if (r_ > top_) {
    if (b >= 0.0 || closest2 >= top_ * top_) return;  // misses the shell
    const double t_in = -b - std::sqrt(top_ * top_ - closest2);
    mu_at = std::clamp((b + t_in) / top_, -1.0, 1.0);
  }
  const double to_top = geometry_.distance_to_top_m(r_at_, mu_at);
  const double x_mu = d_max_ > d_min_ ? (to_top - d_min_) / (d_max_ - d_min_) : 0.0;
  const double u = atmosphere::lut::texture_coord_from_unit(std::clamp(x_mu, 0.0, 1.0), width_);
  const double x = u * double(width_) - 0.5, fx = std::floor(x), wx = x - fx;
  const auto last = static_cast<std::ptrdiff_t>(width_) - 1;
  const double* t0 =
      &row_[static_cast<std::size_t>(std::clamp(static_cast<std::ptrdiff_t>(fx), std::ptrdiff_t{0}, last)) * channels_];
  const double* t1 =
      &row_[static_cast<std::size_t>(std::clamp(static_cast<std::ptrdiff_t>(fx) + 1, std::ptrdiff_t{0}, last)) *
            channels_];
  for (std::size_t c = 0; c < channels_; ++c) out[c] = std::clamp((1.0 - wx) * t0[c] + wx * t1[c], 0.0, 1.0);
}

}  // namespace zenith::render
