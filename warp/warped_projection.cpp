#include "warp/warped_projection.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include <glm/geometric.hpp>

namespace zenith::warp {
namespace {

constexpr int kCoarseSide = 64;  // the inverse starts from at most 64 × 64 nodes
constexpr int kStarts = 4;       // ... the nearest four of them
constexpr int kNewtonIterations = 50;
constexpr double kConvergedBasePx = 1e-7;
constexpr double kBulgeMargin = 1.25;

}  // namespace

WarpedProjection::WarpedProjection(int width_px, int height_px, WarpMesh mesh, std::shared_ptr<const Projection> base)
    : Projection(width_px, height_px), mesh_(std::move(mesh)), base_(std::move(base)) {
  if (!base_) throw std::invalid_argument("WarpedProjection: the base projection is null");

  const WarpMesh::Extent& e = mesh_.extent();
  const auto node_s = [&](int i) { return e.s_min + (e.s_max - e.s_min) * i / (mesh_.columns() - 1); };
  const auto node_t = [&](int j) { return e.t_min + (e.t_max - e.t_min) * j / (mesh_.rows() - 1); };

  // The nodes that reach the image: a mesh running past the image's edges
  // (a Bourke mesh fitted to a narrower output) has nodes no pixel shows.
  max_pixel_angle_rad_ = bound_within(0.0, 0.0, width(), height());

  const int step_i = std::max(1, (mesh_.columns() + kCoarseSide - 1) / kCoarseSide);
  const int step_j = std::max(1, (mesh_.rows() + kCoarseSide - 1) / kCoarseSide);
  for (int j = 0; j < mesh_.rows(); j += step_j)
    for (int i = 0; i < mesh_.columns(); i += step_i)
      if (const WarpNode& n = mesh_.node(i, j); n.valid) coarse_nodes_.emplace_back(node_s(i), node_t(j), n.u, n.v);
  if (coarse_nodes_.empty())  // every valid node fell between the strides
    for (int j = 0; j < mesh_.rows(); ++j)
      for (int i = 0; i < mesh_.columns(); ++i)
        if (const WarpNode& n = mesh_.node(i, j); n.valid) coarse_nodes_.emplace_back(node_s(i), node_t(j), n.u, n.v);
}

double WarpedProjection::stretch_between_nodes(int i0, int i1, int j0, int j1) const {
  const WarpMesh::Extent& e = mesh_.extent();
  // Projector pixels between neighbouring nodes across and down.
  const double step_x_px = (e.s_max - e.s_min) / (mesh_.columns() - 1) * width();
  const double step_y_px = (e.t_max - e.t_min) / (mesh_.rows() - 1) * height();
  const double wb = base_->width(), hb = base_->height();
  const std::array<std::array<int, 2>, 4> neighbours{{{1, 0}, {0, 1}, {1, 1}, {1, -1}}};
  double stretch = 0.0;
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) {
      const WarpNode& a = mesh_.node(i, j);
      if (!a.valid) continue;
      for (const auto& [di, dj] : neighbours) {
        const int i2 = i + di, j2 = j + dj;
        if (i2 > i1 || j2 < j0 || j2 > j1) continue;
        const WarpNode& b = mesh_.node(i2, j2);
        if (!b.valid) continue;
        const double projector_px = std::hypot(di * step_x_px, dj * step_y_px);
        const double base_px = std::hypot((b.u - a.u) * wb, (b.v - a.v) * hb);
        stretch = std::max(stretch, base_px / projector_px);
      }
    }
  return stretch;
}

double WarpedProjection::pixel_angle_bound(double stretch) const {
  return base_->max_pixel_angle_rad() * std::max(1.0, stretch) * kBulgeMargin;
}

std::optional<glm::dvec2> WarpedProjection::source_uv(double s, double t) const {
  const auto sample = mesh_.sample(s, t);
  if (!sample) return std::nullopt;
  return glm::dvec2(sample->u, sample->v);
}

std::optional<glm::dvec2> WarpedProjection::source_pixel(double x_px, double y_px) const {
  const auto uv = source_uv(x_px / width(), y_px / height());
  if (!uv) return std::nullopt;
  return glm::dvec2((*uv).x * base_->width(), (*uv).y * base_->height());
}

double WarpedProjection::intensity(double x_px, double y_px) const {
  const auto sample = mesh_.sample(x_px / width(), y_px / height());
  return sample ? sample->intensity : 0.0;
}

std::optional<glm::dvec3> WarpedProjection::ray(double x_px, double y_px) const {
  const auto source = source_pixel(x_px, y_px);
  if (!source) return std::nullopt;
  return base_->ray(source->x, source->y);
}

std::optional<glm::dvec2> WarpedProjection::pixel(const glm::dvec3& direction) const {
  const auto target_px = base_->pixel(direction);
  if (!target_px) return std::nullopt;
  const glm::dvec2 scale(base_->width(), base_->height());
  const glm::dvec2 target = *target_px / scale;  // (u, v)

  // Starts: the coarse nodes nearest to the target in (u, v).
  std::vector<std::pair<double, std::size_t>> by_distance;
  by_distance.reserve(coarse_nodes_.size());
  for (std::size_t k = 0; k < coarse_nodes_.size(); ++k) {
    const glm::dvec2 d = (glm::dvec2(coarse_nodes_[k].z, coarse_nodes_[k].w) - target) * scale;
    by_distance.emplace_back(glm::dot(d, d), k);
  }
  const std::size_t starts = std::min<std::size_t>(kStarts, by_distance.size());
  std::partial_sort(by_distance.begin(), by_distance.begin() + static_cast<std::ptrdiff_t>(starts), by_distance.end());

  const WarpMesh::Extent& e = mesh_.extent();
  const double h_s = 1e-6 * (e.s_max - e.s_min), h_t = 1e-6 * (e.t_max - e.t_min);
  // Central difference where both sides have data, one-sided otherwise.
  const auto derivative = [&](glm::dvec2 st, glm::dvec2 step, glm::dvec2 at) -> std::optional<glm::dvec2> {
    const auto plus = source_uv(st.x + step.x, st.y + step.y);
    const auto minus = source_uv(st.x - step.x, st.y - step.y);
    const double h = step.x + step.y;
    if (plus && minus) return (*plus - *minus) / (2.0 * h);
    if (plus) return (*plus - at) / h;
    if (minus) return (at - *minus) / h;
    return std::nullopt;
  };

  for (std::size_t start = 0; start < starts; ++start) {
    const glm::dvec4& node = coarse_nodes_[by_distance[start].second];
    glm::dvec2 st(node.x, node.y);
    auto uv = source_uv(st.x, st.y);
    if (!uv) continue;
    double error_px = glm::length((*uv - target) * scale);
    for (int iteration = 0; iteration < kNewtonIterations && error_px > kConvergedBasePx; ++iteration) {
      const auto d_ds = derivative(st, {h_s, 0.0}, *uv);
      const auto d_dt = derivative(st, {0.0, h_t}, *uv);
      if (!d_ds || !d_dt) break;
      const double det = d_ds->x * d_dt->y - d_ds->y * d_dt->x;
      if (!(std::abs(det) > 0.0) || !std::isfinite(det)) break;
      const glm::dvec2 r = *uv - target;
      glm::dvec2 step((r.x * d_dt->y - r.y * d_dt->x) / det, (d_ds->x * r.y - d_ds->y * r.x) / det);
      // Damped: halve the step until it lands on data and reduces the error.
      bool improved = false;
      for (int halving = 0; halving < 30 && !improved; ++halving, step *= 0.5) {
        const glm::dvec2 next = st - step;
        const auto next_uv = source_uv(next.x, next.y);
        if (!next_uv) continue;
        const double next_error = glm::length((*next_uv - target) * scale);
        if (next_error < error_px) {
          st = next, uv = next_uv, error_px = next_error;
          improved = true;
        }
      }
      if (!improved) break;
    }
    if (error_px <= kConvergedBasePx) return glm::dvec2(st.x * width(), st.y * height());
  }
  return std::nullopt;
}

GpuProjection WarpedProjection::gpu() const {
  // The mesh has no closed form: the renderer tabulates ray() per band.
  GpuProjection g;
  g.kind = ProjectionKind::ray_table;
  return g;
}

std::string WarpedProjection::describe() const {
  std::string source = mesh_.source();
  if (const std::size_t slash = source.find_last_of('/'); slash != std::string::npos) source.erase(0, slash + 1);
  return "warped " + std::to_string(width()) + "\u00d7" + std::to_string(height()) + " (mesh " +
         std::to_string(mesh_.columns()) + "\u00d7" + std::to_string(mesh_.rows()) +
         (mesh_.interpolation() == WarpInterpolation::catmull_rom ? " catmull-rom" : " bilinear") +
         (source.empty() ? std::string() : " from " + source) + ") over " + base_->describe();
}

double WarpedProjection::max_pixel_angle_rad() const { return max_pixel_angle_rad_; }

double WarpedProjection::max_pixel_angle_rad_within(double x0_px, double y0_px, double x1_px, double y1_px) const {
  if (!(std::isfinite(x0_px) && std::isfinite(y0_px) && std::isfinite(x1_px) && std::isfinite(y1_px)))
    return max_pixel_angle_rad_;
  // Within the image: what lies outside it has no pixel.
  const double x0 = std::clamp(std::min(x0_px, x1_px), 0.0, double(width()));
  const double x1 = std::clamp(std::max(x0_px, x1_px), 0.0, double(width()));
  const double y0 = std::clamp(std::min(y0_px, y1_px), 0.0, double(height()));
  const double y1 = std::clamp(std::max(y0_px, y1_px), 0.0, double(height()));
  if (!(x0 < x1 && y0 < y1)) return pixel_angle_bound(0.0);  // no pixel of the image
  return bound_within(x0, y0, x1, y1);
}

double WarpedProjection::bound_within(double x0_px, double y0_px, double x1_px, double y1_px) const {
  // The rectangle in cells: fractional node indices of its corners.
  const WarpMesh::Extent& e = mesh_.extent();
  const int columns = mesh_.columns(), rows = mesh_.rows();
  const double f_x0 = (x0_px / width() - e.s_min) / (e.s_max - e.s_min) * (columns - 1);
  const double f_x1 = (x1_px / width() - e.s_min) / (e.s_max - e.s_min) * (columns - 1);
  const double f_y0 = (y0_px / height() - e.t_min) / (e.t_max - e.t_min) * (rows - 1);
  const double f_y1 = (y1_px / height() - e.t_min) / (e.t_max - e.t_min) * (rows - 1);
  if (f_x1 < 0.0 || f_y1 < 0.0 || f_x0 > columns - 1 || f_y0 > rows - 1) return pixel_angle_bound(0.0);
  // The cells the half-open rectangle [x0, x1) × [y0, y1) overlaps (a pixel
  // ending on a node does not reach the next cell), then the nodes of their
  // 4 × 4 stencils.
  const auto first_cell = [](double f, int cells) { return std::clamp(static_cast<int>(std::floor(f)), 0, cells - 1); };
  const auto last_cell = [](double f, int cells) {
    return std::clamp(static_cast<int>(std::ceil(f)) - 1, 0, cells - 1);
  };
  const int c0 = first_cell(f_x0, columns - 1), c1 = std::max(c0, last_cell(f_x1, columns - 1));
  const int r0 = first_cell(f_y0, rows - 1), r1 = std::max(r0, last_cell(f_y1, rows - 1));
  return pixel_angle_bound(stretch_between_nodes(std::max(0, c0 - 1), std::min(columns - 1, c1 + 2),
                                                 std::max(0, r0 - 1), std::min(rows - 1, r1 + 2)));
}

std::optional<double> WarpedProjection::local_stretch(double x_px, double y_px) const {
  const auto centre = source_pixel(x_px, y_px);
  // ∂(source px)/∂(projector px) along one axis over ±½ px: central where both
  // sides have data, one-sided (over ½ px) where one has, nothing where neither.
  const auto column = [&](double dx, double dy) -> std::optional<glm::dvec2> {
    const auto plus = source_pixel(x_px + 0.5 * dx, y_px + 0.5 * dy);
    const auto minus = source_pixel(x_px - 0.5 * dx, y_px - 0.5 * dy);
    if (plus && minus) return *plus - *minus;
    if (plus && centre) return 2.0 * (*plus - *centre);
    if (minus && centre) return 2.0 * (*centre - *minus);
    return std::nullopt;
  };
  const auto jx = column(1.0, 0.0), jy = column(0.0, 1.0);
  if (!jx || !jy) return std::nullopt;
  // Largest singular value of J = [jx jy]: σ² = (S + √(S² − 4D²)) / 2 with
  // S = ‖J‖²_F and D = det J.
  const double frobenius2 = glm::dot(*jx, *jx) + glm::dot(*jy, *jy);
  const double det = jx->x * jy->y - jx->y * jy->x;
  const double sigma =
      std::sqrt(0.5 * (frobenius2 + std::sqrt(std::max(0.0, frobenius2 * frobenius2 - 4.0 * det * det))));
  if (!std::isfinite(sigma)) return std::nullopt;
  return sigma;
}

double WarpedProjection::pixel_angle_rad_at(const glm::dvec3& direction) const {
  const double base_angle = base_->pixel_angle_rad_at(direction);
  // A degenerate spot (the mesh constant there) would give a zero footprint,
  // and the renderer divides by it: a hundredth of a base footprint at least.
  const auto sized = [&](double stretch) { return base_angle * std::max(stretch, 1e-2); };
  if (const auto p = pixel(direction))
    if (const auto k = local_stretch(p->x, p->y)) return sized(*k);
  // Off the mesh: the valid coarse node whose ray is nearest to the direction.
  const glm::dvec3 d = glm::normalize(direction);
  double best_cos = -2.0;
  std::optional<double> best;
  for (const glm::dvec4& node : coarse_nodes_) {
    const auto r = base_->ray(node.z * base_->width(), node.w * base_->height());
    if (!r) continue;
    const double c = glm::dot(*r, d);
    if (c <= best_cos) continue;
    if (const auto k = local_stretch(node.x * width(), node.y * height())) best_cos = c, best = *k;
  }
  return best ? sized(*best) : max_pixel_angle_rad();
}

}  // namespace zenith::warp
