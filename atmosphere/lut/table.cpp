#include "atmosphere/lut/table.h"

#include <algorithm>
#include <cmath>

namespace zenith::atmosphere::lut {

namespace {

/// GL_LINEAR + GL_CLAMP_TO_EDGE along one axis: the two texels and the weight of the second.
struct Lerp {
  std::size_t i0, i1;
  double t;
};

Lerp linear_taps(double u, std::size_t n) {
  const double x = u * double(n) - 0.5;
  const double f = std::floor(x);
  const double t = x - f;
  const long long i = static_cast<long long>(f);
  const long long last = static_cast<long long>(n) - 1;
  return {std::size_t(std::clamp(i, 0LL, last)), std::size_t(std::clamp(i + 1, 0LL, last)), t};
}

}  // namespace

void Table2D::sample(double u, double v, double* out) const {
  const Lerp a = linear_taps(u, width), b = linear_taps(v, height);
  const float *p00 = texel(a.i0, b.i0), *p10 = texel(a.i1, b.i0), *p01 = texel(a.i0, b.i1), *p11 = texel(a.i1, b.i1);
  const double w00 = (1 - a.t) * (1 - b.t), w10 = a.t * (1 - b.t), w01 = (1 - a.t) * b.t, w11 = a.t * b.t;
  for (std::size_t c = 0; c < channels; ++c) out[c] = w00 * p00[c] + w10 * p10[c] + w01 * p01[c] + w11 * p11[c];
}

void Table3D::sample(double u, double v, double w, double* out) const {
  const Lerp a = linear_taps(u, width), b = linear_taps(v, height), d = linear_taps(w, depth);
  for (std::size_t c = 0; c < channels; ++c) out[c] = 0.0;
  const std::size_t xs[2] = {a.i0, a.i1}, ys[2] = {b.i0, b.i1}, zs[2] = {d.i0, d.i1};
  const double wx[2] = {1 - a.t, a.t}, wy[2] = {1 - b.t, b.t}, wz[2] = {1 - d.t, d.t};
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        const double weight = wx[i] * wy[j] * wz[k];
        if (weight == 0.0) continue;
        const float* p = texel(xs[i], ys[j], zs[k]);
        for (std::size_t c = 0; c < channels; ++c) out[c] += weight * p[c];
      }
}

}  // namespace zenith::atmosphere::lut
