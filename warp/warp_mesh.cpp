#include "warp/warp_mesh.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string_view>

#include <spdlog/spdlog.h>

#include "core/files.h"
#include "warp/warp_map_checks.h"

namespace zenith::warp {
namespace {

constexpr int kMinNodes = 2;
constexpr int kMaxNodesPerSide = 16384;
constexpr std::size_t kMaxNodes = std::size_t{1} << 24;  // 16 M nodes: far past any real mesh
constexpr int kMaxResampleNodes = 4096;

std::string number(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

/// Catmull–Rom weights of the nodes at −1, 0, 1, 2 for a position a ∈ [0, 1] between 0 and 1.
std::array<double, 4> catmull_rom_weights(double a) {
  const double a2 = a * a, a3 = a2 * a;
  return {0.5 * (-a3 + 2.0 * a2 - a), 0.5 * (3.0 * a3 - 5.0 * a2 + 2.0), 0.5 * (-3.0 * a3 + 4.0 * a2 + a),
          0.5 * (a3 - a2)};
}

struct NodeValue {
  double u, v, intensity;
  bool valid;
};

/// Node (i, j) of the mesh, extended by one node past each border by linear
/// extrapolation (2·p0 − p1), valid where its sources are.
NodeValue extended_node(const WarpMesh& mesh, int i, int j) {
  const int last_i = mesh.columns() - 1, last_j = mesh.rows() - 1;
  const auto extrapolate = [](const NodeValue& p0, const NodeValue& p1) {
    return NodeValue{2.0 * p0.u - p1.u, 2.0 * p0.v - p1.v, 2.0 * p0.intensity - p1.intensity, p0.valid && p1.valid};
  };
  if (i < 0) return extrapolate(extended_node(mesh, 0, j), extended_node(mesh, 1, j));
  if (i > last_i) return extrapolate(extended_node(mesh, last_i, j), extended_node(mesh, last_i - 1, j));
  if (j < 0) return extrapolate(extended_node(mesh, i, 0), extended_node(mesh, i, 1));
  if (j > last_j) return extrapolate(extended_node(mesh, i, last_j), extended_node(mesh, i, last_j - 1));
  const WarpNode& node = mesh.node(i, j);
  return {node.u, node.v, node.intensity, node.valid};
}

// ---- Bourke .data parsing ------------------------------------------------------

struct TextLine {
  int number;
  std::string_view text;
};

std::vector<TextLine> split_lines(std::string_view bytes) {
  std::vector<TextLine> lines;
  std::size_t start = 0;
  int number_1 = 1;
  while (start < bytes.size()) {
    std::size_t end = bytes.find('\n', start);
    if (end == std::string_view::npos) end = bytes.size();
    std::string_view text = bytes.substr(start, end - start);
    if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
    lines.push_back({number_1++, text});
    start = end + 1;
  }
  return lines;
}

std::vector<std::string_view> fields_of(std::string_view text) {
  std::vector<std::string_view> fields;
  std::size_t pos = 0;
  const auto space = [](char c) { return c == ' ' || c == '\t' || c == '\v' || c == '\f'; };
  while (pos < text.size()) {
    while (pos < text.size() && space(text[pos])) ++pos;
    const std::size_t start = pos;
    while (pos < text.size() && !space(text[pos])) ++pos;
    if (pos > start) fields.push_back(text.substr(start, pos - start));
  }
  return fields;
}

std::string shown(std::string_view token) {
  std::string out;
  for (char c : token.substr(0, 32)) out += (c >= 0x20 && c < 0x7f) ? c : '?';
  if (token.size() > 32) out += "...";
  return out;
}

class BourkeParser {
 public:
  explicit BourkeParser(const std::filesystem::path& path) : name_(path.string()) {}

  [[noreturn]] void fail(int line, const std::string& what) const {
    throw std::runtime_error(name_ + ":" + std::to_string(line) + ": " + what);
  }
  [[noreturn]] void fail(const std::string& what) const { throw std::runtime_error(name_ + ": " + what); }

  long long integer_field(int line, const char* field, std::string_view text) const {
    long long value = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error != std::errc() || end != text.data() + text.size())
      fail(line, std::string("field '") + field + "' = '" + shown(text) + "' is not an integer");
    return value;
  }

  double real_field(int line, const char* field, std::string_view text) const {
    std::string_view digits = text;
    if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);  // some writers print "+0.5"
    double value = 0.0;
    const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    if (digits.empty() || error != std::errc() || end != digits.data() + digits.size())
      fail(line, std::string("field '") + field + "' = '" + shown(text) + "' is not a number");
    return value;
  }

  const std::string& name() const { return name_; }

 private:
  std::string name_;
};

struct BourkeNode {
  double s, t;  // projector position, normalized, top-left origin
  WarpNode data;
};

/// The (a, b) ∈ [0, 1]² with bilinear(p00, p10, p01, p11; a, b) = (s, t), if any
/// (Newton's method from the quad's centre).
std::optional<std::array<double, 2>> invert_bilinear(const std::array<std::array<double, 2>, 4>& p, double s,
                                                     double t) {
  double a = 0.5, b = 0.5;
  for (int iteration = 0; iteration < 40; ++iteration) {
    std::array<double, 2> f{}, da{}, db{};
    for (int k = 0; k < 2; ++k) {
      f[k] = (1 - a) * (1 - b) * p[0][k] + a * (1 - b) * p[1][k] + (1 - a) * b * p[2][k] + a * b * p[3][k] -
             (k == 0 ? s : t);
      da[k] = (1 - b) * (p[1][k] - p[0][k]) + b * (p[3][k] - p[2][k]);
      db[k] = (1 - a) * (p[2][k] - p[0][k]) + a * (p[3][k] - p[1][k]);
    }
    const double det = da[0] * db[1] - da[1] * db[0];
    if (std::abs(det) < 1e-300) return std::nullopt;
    const double step_a = (f[0] * db[1] - f[1] * db[0]) / det;
    const double step_b = (da[0] * f[1] - da[1] * f[0]) / det;
    a -= step_a;
    b -= step_b;
    if (!std::isfinite(a) || !std::isfinite(b)) return std::nullopt;
    if (std::abs(step_a) < 1e-13 && std::abs(step_b) < 1e-13) break;
  }
  constexpr double kSlack = 1e-9;
  if (a < -kSlack || a > 1 + kSlack || b < -kSlack || b > 1 + kSlack) return std::nullopt;
  return std::array<double, 2>{std::clamp(a, 0.0, 1.0), std::clamp(b, 0.0, 1.0)};
}

/// Resamples a mesh whose node positions are not a regular grid onto one.
WarpMesh resample_bourke(const std::vector<BourkeNode>& nodes, int nx, int ny, const std::string& name,
                         const BourkeMeshOptions& options) {
  const auto at = [&](int i, int j) -> const BourkeNode& { return nodes[static_cast<std::size_t>(j) * nx + i]; };
  const auto quad_used = [&](int i, int j) {
    return at(i, j).data.valid && at(i + 1, j).data.valid && at(i, j + 1).data.valid && at(i + 1, j + 1).data.valid;
  };
  WarpMesh::Extent extent{std::numeric_limits<double>::max(), std::numeric_limits<double>::lowest(),
                          std::numeric_limits<double>::max(), std::numeric_limits<double>::lowest()};
  for (int j = 0; j + 1 < ny; ++j)
    for (int i = 0; i + 1 < nx; ++i)
      if (quad_used(i, j))
        for (int k = 0; k < 4; ++k) {
          const BourkeNode& n = at(i + (k & 1), j + (k >> 1));
          extent.s_min = std::min(extent.s_min, n.s);
          extent.s_max = std::max(extent.s_max, n.s);
          extent.t_min = std::min(extent.t_min, n.t);
          extent.t_max = std::max(extent.t_max, n.t);
        }
  if (!(extent.s_min < extent.s_max && extent.t_min < extent.t_max))
    throw std::runtime_error(name + ": the warp mesh has no quad of four used nodes (NaN-only mesh)");

  const auto resolution = [](std::optional<int> requested, int n, const char* what, const std::string& file) {
    const int value = requested.value_or(std::min(4 * (n - 1) + 1, 1025));
    if (value < kMinNodes || value > kMaxResampleNodes)
      throw std::invalid_argument(file + ": " + what + " = " + std::to_string(value) + ": must be in [2, " +
                                  std::to_string(kMaxResampleNodes) + "]");
    return value;
  };
  const int columns = resolution(options.resample_columns, nx, "resample_columns", name);
  const int rows = resolution(options.resample_rows, ny, "resample_rows", name);
  const double ds = (extent.s_max - extent.s_min) / (columns - 1);
  const double dt = (extent.t_max - extent.t_min) / (rows - 1);

  std::vector<WarpNode> grid(static_cast<std::size_t>(columns) * rows);
  for (int j = 0; j + 1 < ny; ++j) {
    for (int i = 0; i + 1 < nx; ++i) {
      if (!quad_used(i, j)) continue;
      const BourkeNode* q[4] = {&at(i, j), &at(i + 1, j), &at(i, j + 1), &at(i + 1, j + 1)};
      std::array<std::array<double, 2>, 4> corners{};
      double lo_s = q[0]->s, hi_s = q[0]->s, lo_t = q[0]->t, hi_t = q[0]->t;
      for (int k = 0; k < 4; ++k) {
        corners[k] = {q[k]->s, q[k]->t};
        lo_s = std::min(lo_s, q[k]->s), hi_s = std::max(hi_s, q[k]->s);
        lo_t = std::min(lo_t, q[k]->t), hi_t = std::max(hi_t, q[k]->t);
      }
      const int p0 = std::max(0, static_cast<int>(std::ceil((lo_s - extent.s_min) / ds - 1e-9)));
      const int p1 = std::min(columns - 1, static_cast<int>(std::floor((hi_s - extent.s_min) / ds + 1e-9)));
      const int r0 = std::max(0, static_cast<int>(std::ceil((lo_t - extent.t_min) / dt - 1e-9)));
      const int r1 = std::min(rows - 1, static_cast<int>(std::floor((hi_t - extent.t_min) / dt + 1e-9)));
      for (int r = r0; r <= r1; ++r) {
        for (int p = p0; p <= p1; ++p) {
          WarpNode& target = grid[static_cast<std::size_t>(r) * columns + p];
          if (target.valid) continue;  // a folded mesh: the first quad wins
          const auto ab = invert_bilinear(corners, extent.s_min + p * ds, extent.t_min + r * dt);
          if (!ab) continue;
          const double a = (*ab)[0], b = (*ab)[1];
          const double w[4] = {(1 - a) * (1 - b), a * (1 - b), (1 - a) * b, a * b};
          target = {0.0, 0.0, 0.0, true};
          for (int k = 0; k < 4; ++k) {
            target.u += w[k] * q[k]->data.u;
            target.v += w[k] * q[k]->data.v;
            target.intensity += w[k] * q[k]->data.intensity;
          }
          target.intensity = std::clamp(target.intensity, 0.0, 1.0);
        }
      }
    }
  }
  return WarpMesh(columns, rows, std::move(grid), name, WarpInterpolation::catmull_rom, extent);
}

}  // namespace

// ---- WarpMesh ---------------------------------------------------------------------

WarpMesh::WarpMesh(int columns, int rows, std::vector<WarpNode> nodes, std::string source,
                   WarpInterpolation interpolation, Extent extent)
    : columns_(columns),
      rows_(rows),
      nodes_(std::move(nodes)),
      source_(std::move(source)),
      interpolation_(interpolation),
      extent_(extent) {
  const auto fail = [&](const std::string& what) { throw std::invalid_argument(source_ + ": " + what); };
  if (columns_ < kMinNodes || columns_ > kMaxNodesPerSide || rows_ < kMinNodes || rows_ > kMaxNodesPerSide)
    fail("warp mesh of " + std::to_string(columns_) + "x" + std::to_string(rows_) +
         " nodes: each side must be in [2, 16384]");
  if (nodes_.size() != static_cast<std::size_t>(columns_) * rows_)
    fail("warp mesh of " + std::to_string(columns_) + "x" + std::to_string(rows_) + " nodes given " +
         std::to_string(nodes_.size()) + " nodes");
  if (!(std::isfinite(extent_.s_min) && std::isfinite(extent_.s_max) && std::isfinite(extent_.t_min) &&
        std::isfinite(extent_.t_max) && extent_.s_min < extent_.s_max && extent_.t_min < extent_.t_max))
    fail("warp mesh extent [" + number(extent_.s_min) + ", " + number(extent_.s_max) + "] x [" + number(extent_.t_min) +
         ", " + number(extent_.t_max) + "] is empty or not finite");
  for (const WarpNode& node : nodes_) {
    if (!node.valid) continue;
    if (!std::isfinite(node.u) || !std::isfinite(node.v) || !(node.intensity >= 0.0 && node.intensity <= 1.0))
      fail("warp mesh node (u " + number(node.u) + ", v " + number(node.v) + ", intensity " + number(node.intensity) +
           ") must be finite with intensity in [0, 1]");
    ++valid_count_;
  }
  if (valid_count_ == 0) fail("the warp mesh has no valid node (NaN-only mesh)");
}

std::optional<WarpMesh::Sample> WarpMesh::sample(double s, double t) const {
  if (!std::isfinite(s) || !std::isfinite(t)) return std::nullopt;
  if (s < extent_.s_min || s > extent_.s_max || t < extent_.t_min || t > extent_.t_max) return std::nullopt;
  const double fx = (s - extent_.s_min) / (extent_.s_max - extent_.s_min) * (columns_ - 1);
  const double fy = (t - extent_.t_min) / (extent_.t_max - extent_.t_min) * (rows_ - 1);
  const int i0 = std::clamp(static_cast<int>(std::floor(fx)), 0, columns_ - 2);
  const int j0 = std::clamp(static_cast<int>(std::floor(fy)), 0, rows_ - 2);
  const double a = fx - i0, b = fy - j0;

  const WarpNode& n00 = node(i0, j0);
  const WarpNode& n10 = node(i0 + 1, j0);
  const WarpNode& n01 = node(i0, j0 + 1);
  const WarpNode& n11 = node(i0 + 1, j0 + 1);
  if (!(n00.valid && n10.valid && n01.valid && n11.valid)) return std::nullopt;

  if (interpolation_ == WarpInterpolation::catmull_rom) {
    const std::array<double, 4> wa = catmull_rom_weights(a), wb = catmull_rom_weights(b);
    Sample sum{0.0, 0.0, 0.0};
    bool all_valid = true;
    for (int dj = 0; dj < 4 && all_valid; ++dj) {
      for (int di = 0; di < 4; ++di) {
        const NodeValue p = extended_node(*this, i0 - 1 + di, j0 - 1 + dj);
        if (!p.valid) {
          all_valid = false;
          break;
        }
        const double w = wa[di] * wb[dj];
        sum.u += w * p.u;
        sum.v += w * p.v;
        sum.intensity += w * p.intensity;
      }
    }
    if (all_valid) {
      sum.intensity = std::clamp(sum.intensity, 0.0, 1.0);
      return sum;
    }
  }
  const double w00 = (1 - a) * (1 - b), w10 = a * (1 - b), w01 = (1 - a) * b, w11 = a * b;
  return Sample{
      w00 * n00.u + w10 * n10.u + w01 * n01.u + w11 * n11.u, w00 * n00.v + w10 * n10.v + w01 * n01.v + w11 * n11.v,
      std::clamp(w00 * n00.intensity + w10 * n10.intensity + w01 * n01.intensity + w11 * n11.intensity, 0.0, 1.0)};
}

// ---- Loaders ------------------------------------------------------------------------

const char* to_string(MeshFit fit) {
  switch (fit) {
    case MeshFit::height: return "height";
    case MeshFit::width: return "width";
    case MeshFit::crop: return "crop";
    case MeshFit::letterbox: return "letterbox";
    case MeshFit::stretch: return "stretch";
  }
  return "?";
}

BourkeFrame bourke_frame(MeshFit fit, double mesh_aspect, double output_aspect) {
  if (!(mesh_aspect > 0.0 && output_aspect > 0.0 && std::isfinite(mesh_aspect) && std::isfinite(output_aspect)))
    throw std::invalid_argument("bourke_frame: aspect ratios must be finite and > 0, got mesh " + number(mesh_aspect) +
                                ", output " + number(output_aspect));
  const bool wider = mesh_aspect >= output_aspect;
  if (fit == MeshFit::crop) fit = wider ? MeshFit::height : MeshFit::width;
  if (fit == MeshFit::letterbox) fit = wider ? MeshFit::width : MeshFit::height;
  switch (fit) {
    case MeshFit::height: return {output_aspect, 1.0};
    case MeshFit::width: return {mesh_aspect, mesh_aspect / output_aspect};
    default: return {mesh_aspect, 1.0};  // stretch
  }
}

WarpMesh load_bourke_mesh(const std::filesystem::path& path, const BourkeMeshOptions& options) {
  const BourkeParser parser(path);
  const std::string bytes = core::file_bytes(path);
  const std::vector<TextLine> lines = split_lines(bytes);

  // Line 1: the mesh type.
  if (lines.empty()) parser.fail("truncated: empty file (expected the mesh type on line 1)");
  {
    const auto fields = fields_of(lines[0].text);
    if (fields.size() != 1) parser.fail(1, "expected 1 field (mesh type), found " + std::to_string(fields.size()));
    const long long type = parser.integer_field(1, "mesh type", fields[0]);
    if (type == 1) parser.fail(1, "mesh type 1 (polar) is not supported, only 2 (rectangular)");
    if (type != 2) parser.fail(1, "mesh type " + std::to_string(type) + ": must be 2 (rectangular)");
  }
  // Line 2: nx ny.
  if (lines.size() < 2) parser.fail("truncated: expected 'nx ny' on line 2");
  const auto size_fields = fields_of(lines[1].text);
  if (size_fields.size() != 2) parser.fail(2, "expected 2 fields (nx ny), found " + std::to_string(size_fields.size()));
  const long long nx_ll = parser.integer_field(2, "nx", size_fields[0]);
  const long long ny_ll = parser.integer_field(2, "ny", size_fields[1]);
  if (nx_ll < kMinNodes || nx_ll > kMaxNodesPerSide)
    parser.fail(2, "field 'nx' = " + std::to_string(nx_ll) + ": must be in [2, 16384]");
  if (ny_ll < kMinNodes || ny_ll > kMaxNodesPerSide)
    parser.fail(2, "field 'ny' = " + std::to_string(ny_ll) + ": must be in [2, 16384]");
  const int nx = static_cast<int>(nx_ll), ny = static_cast<int>(ny_ll);
  const std::size_t expected = static_cast<std::size_t>(nx) * ny;
  if (expected > kMaxNodes)
    parser.fail(2, "nx x ny = " + std::to_string(expected) + " nodes: at most " + std::to_string(kMaxNodes));

  // Node lines, rows from the bottom; stored here row by row from the top.
  std::vector<BourkeNode> nodes(expected);
  std::size_t count = 0;
  int last_line = 2;
  static constexpr const char* kFieldNames[5] = {"x", "y", "u", "v", "intensity"};
  for (std::size_t k = 2; k < lines.size(); ++k) {
    const TextLine& line = lines[k];
    const auto fields = fields_of(line.text);
    if (fields.empty()) continue;
    if (count == expected)
      parser.fail(line.number, "more than nx x ny = " + std::to_string(nx) + " x " + std::to_string(ny) + " = " +
                                   std::to_string(expected) + " nodes (wrong counts on line 2?)");
    if (fields.size() != 5)
      parser.fail(line.number, "expected 5 fields (x y u v intensity), found " + std::to_string(fields.size()));
    double value[5];
    for (int f = 0; f < 5; ++f) value[f] = parser.real_field(line.number, kFieldNames[f], fields[f]);
    for (int f = 0; f < 2; ++f)
      if (!std::isfinite(value[f]))
        parser.fail(line.number,
                    std::string("field '") + kFieldNames[f] + "' = '" + shown(fields[f]) + "' must be finite");
    const int column = static_cast<int>(count % nx);
    const int row_from_bottom = static_cast<int>(count / nx);
    BourkeNode& node = nodes[static_cast<std::size_t>(ny - 1 - row_from_bottom) * nx + column];
    node.s = value[0];  // x, y for now: the aspect is known only at the end
    node.t = value[1];
    const double u = value[2], v = value[3], intensity = value[4];
    const bool used = std::isfinite(u) && std::isfinite(v) && std::isfinite(intensity) && u >= 0.0 && u <= 1.0 &&
                      v >= 0.0 && v <= 1.0 && intensity >= 0.0;
    node.data = used ? WarpNode{u, 1.0 - v, std::min(intensity, 1.0), true} : WarpNode{};
    ++count;
    last_line = line.number;
  }
  if (count < expected)
    parser.fail("truncated: " + std::to_string(count) + " of nx x ny = " + std::to_string(nx) + " x " +
                std::to_string(ny) + " = " + std::to_string(expected) + " nodes (last at line " +
                std::to_string(last_line) + ")");

  if (std::none_of(nodes.begin(), nodes.end(), [](const BourkeNode& node) { return node.data.valid; }))
    parser.fail(
        "the warp mesh has no used node (NaN-only mesh): every node has u or v outside [0, 1], a "
        "negative intensity or a non-finite field");

  // Projector coordinates → (s, t), through the fit's frame.
  double mesh_aspect = 0.0;
  for (const BourkeNode& node : nodes) mesh_aspect = std::max(mesh_aspect, std::abs(node.s));
  if (!(mesh_aspect > 0.0)) parser.fail("cannot infer the mesh's aspect ratio: every node has x = 0");
  double output_aspect = mesh_aspect;
  if (options.aspect) {
    output_aspect = *options.aspect;
    if (!(output_aspect > 0.0 && output_aspect <= 100.0))
      throw std::invalid_argument(parser.name() + ": aspect = " + number(output_aspect) + ": must be in (0, 100]");
  }
  const BourkeFrame frame = bourke_frame(options.fit, mesh_aspect, output_aspect);
  for (BourkeNode& node : nodes) {
    node.s = (node.s + frame.half_x) / (2.0 * frame.half_x);
    node.t = (frame.half_y - node.t) / (2.0 * frame.half_y);
  }

  // A regular grid in (x, y), the usual case: use the nodes as they are.
  const auto at = [&](int i, int j) -> const BourkeNode& { return nodes[static_cast<std::size_t>(j) * nx + i]; };
  const WarpMesh::Extent extent{at(0, 0).s, at(nx - 1, 0).s, at(0, 0).t, at(0, ny - 1).t};
  const double ds = (extent.s_max - extent.s_min) / (nx - 1), dt = (extent.t_max - extent.t_min) / (ny - 1);
  bool regular = ds > 0.0 && dt > 0.0;
  const double tolerance = 1e-3 * std::min(ds, dt);
  for (int j = 0; j < ny && regular; ++j)
    for (int i = 0; i < nx && regular; ++i)
      regular = std::abs(at(i, j).s - (extent.s_min + i * ds)) <= tolerance &&
                std::abs(at(i, j).t - (extent.t_min + j * dt)) <= tolerance;
  if (!regular) return resample_bourke(nodes, nx, ny, parser.name(), options);

  std::vector<WarpNode> grid(expected);
  for (std::size_t k = 0; k < expected; ++k) grid[k] = nodes[k].data;
  return WarpMesh(nx, ny, std::move(grid), parser.name(), WarpInterpolation::catmull_rom, extent);
}

WarpMesh warp_mesh_from_pfm(const PfmImage& map, const std::string& source, WarpInterpolation interpolation,
                            const WarpMapConventions& conventions) {
  if (map.channels != 3)
    throw std::invalid_argument(source + ": a warp map needs 3 channels ('PF'), this one has " +
                                std::to_string(map.channels));
  if (map.width < kMinNodes || map.height < kMinNodes)
    throw std::invalid_argument(source + ": a warp map of " + std::to_string(map.width) + "x" +
                                std::to_string(map.height) + " samples: needs at least 2x2");
  std::vector<WarpNode> nodes(static_cast<std::size_t>(map.width) * map.height);
  for (int y = 0; y < map.height; ++y)
    for (int x = 0; x < map.width; ++x) {
      const double u = map.at(x, y, 0), v = map.at(x, y, 1);
      if (!std::isfinite(u) || !std::isfinite(v)) continue;
      const WarpSourcePoint p = to_source_point(u, v, x, map.width, y, map.height, conventions);
      nodes[static_cast<std::size_t>(y) * map.width + x] = {p.u, p.v, 1.0, true};
    }
  WarpMesh mesh(map.width, map.height, std::move(nodes), source, interpolation);
  for (const std::string& warning : warp_map_warnings(map, conventions, source)) spdlog::warn("{}", warning);
  return mesh;
}

WarpMesh load_pfm_warp_mesh(const std::filesystem::path& path, PfmRowOrder stored_rows, WarpInterpolation interpolation,
                            const WarpMapConventions& conventions) {
  return warp_mesh_from_pfm(read_pfm(path, stored_rows), path.string(), interpolation, conventions);
}

}  // namespace zenith::warp
