#include "warp/mpcdi.h"

#include <zip.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <memory>
#include <set>
#include <stdexcept>

#include "warp/xml_reader.h"

namespace zenith::warp {
namespace {

constexpr zip_uint64_t kMaxMemberBytes = zip_uint64_t{1} << 30;  // 1 GiB: far past any warp or blend file
constexpr int kMaxResolutionPx = 65536;

std::string number(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

/// A read-only ZIP archive (libzip).
class ZipArchive {
 public:
  explicit ZipArchive(const std::filesystem::path& path) : name_(path.string()) {
    int code = 0;
    archive_ = zip_open(name_.c_str(), ZIP_RDONLY, &code);
    if (!archive_) {
      zip_error_t error;
      zip_error_init_with_code(&error, code);
      const std::string reason = zip_error_strerror(&error);
      zip_error_fini(&error);
      throw std::runtime_error(name_ + ": cannot open as a ZIP archive (" + reason + ")");
    }
    const zip_int64_t count = zip_get_num_entries(archive_, 0);
    for (zip_int64_t k = 0; k < count; ++k) {
      const char* entry = zip_get_name(archive_, static_cast<zip_uint64_t>(k), 0);
      names_.emplace_back(entry ? entry : "");
    }
  }
  ~ZipArchive() {
    if (archive_) zip_discard(archive_);
  }
  ZipArchive(const ZipArchive&) = delete;
  ZipArchive& operator=(const ZipArchive&) = delete;

  const std::string& name() const { return name_; }
  const std::vector<std::string>& names() const { return names_; }

  /// The index of a member: exact match first, then ignoring case; -1 when absent.
  long long find(const std::string& member) const {
    for (std::size_t k = 0; k < names_.size(); ++k)
      if (names_[k] == member) return static_cast<long long>(k);
    for (std::size_t k = 0; k < names_.size(); ++k)
      if (equals_ignoring_case(names_[k], member)) return static_cast<long long>(k);
    return -1;
  }

  std::string read(long long index) const {
    const std::string& member = names_[static_cast<std::size_t>(index)];
    zip_stat_t stat;
    zip_stat_init(&stat);
    if (zip_stat_index(archive_, static_cast<zip_uint64_t>(index), 0, &stat) != 0 || !(stat.valid & ZIP_STAT_SIZE))
      throw std::runtime_error(name_ + ":" + member + ": cannot read (" + zip_strerror(archive_) + ")");
    if (stat.size > kMaxMemberBytes)
      throw std::runtime_error(name_ + ":" + member + ": " + std::to_string(stat.size) + " bytes: too large");
    std::unique_ptr<zip_file_t, int (*)(zip_file_t*)> file(zip_fopen_index(archive_, static_cast<zip_uint64_t>(index), 0),
                                                         zip_fclose);
    if (!file) throw std::runtime_error(name_ + ":" + member + ": cannot read (" + zip_strerror(archive_) + ")");
    std::string bytes(stat.size, '\0');
    zip_uint64_t done = 0;
    while (done < stat.size) {
      const zip_int64_t got = zip_fread(file.get(), bytes.data() + done, stat.size - done);
      if (got < 0)
        throw std::runtime_error(name_ + ":" + member + ": corrupt (" + zip_file_strerror(file.get()) + ")");
      if (got == 0) break;
      done += static_cast<zip_uint64_t>(got);
    }
    if (done != stat.size) throw std::runtime_error(name_ + ":" + member + ": truncated in the archive");
    return bytes;
  }

 private:
  std::string name_;
  zip_t* archive_ = nullptr;
  std::vector<std::string> names_;
};

/// The base name of a member path.
std::string_view base_name(std::string_view member) {
  const std::size_t slash = member.find_last_of('/');
  return slash == std::string_view::npos ? member : member.substr(slash + 1);
}

/// Reads the elements of mpcdi.xml; every error names the archive, the member and the line.
class MpcdiReader {
 public:
  MpcdiReader(const ZipArchive& zip, std::string xml_member, const MpcdiLoadOptions& options)
      : zip_(zip), xml_member_(std::move(xml_member)), source_(zip.name() + ":" + xml_member_), options_(options) {
    const std::size_t slash = xml_member_.find_last_of('/');
    folder_ = slash == std::string::npos ? "" : xml_member_.substr(0, slash + 1);
  }

  MpcdiFile read() {
    const XmlElement root = parse_xml(zip_.read(zip_.find(xml_member_)), source_);
    if (!root.is("MPCDI")) fail(root, "the root element is <" + root.name + ">, expected <MPCDI>");
    MpcdiFile file;
    file.path = zip_.name();
    const std::string& profile = required_attribute(root, "profile");
    if (equals_ignoring_case(profile, "2d")) {
      file.profile = MpcdiProfile::media_2d;
    } else if (equals_ignoring_case(profile, "3d")) {
      file.profile = MpcdiProfile::simulation_3d;
    } else if (equals_ignoring_case(profile, "a3")) {
      file.profile = MpcdiProfile::advanced_3d;
    } else if (equals_ignoring_case(profile, "sl")) {
      file.profile = MpcdiProfile::shader_lamps;
    } else {
      fail(root, "<MPCDI> attribute 'profile' = '" + profile + "': must be one of 2d, 3d, a3, sl");
    }
    if (const std::string* version = root.attribute("version")) file.version = *version;

    const XmlElement& display = required_child(root, "display");
    std::set<std::string> region_ids;
    for (const XmlElement* buffer_element : display.children_named("buffer")) {
      MpcdiBuffer buffer;
      buffer.id = required_attribute(*buffer_element, "id");
      buffer.x_resolution_px = optional_resolution(*buffer_element, "xResolution");
      buffer.y_resolution_px = optional_resolution(*buffer_element, "yResolution");
      for (const XmlElement* region_element : buffer_element->children_named("region")) {
        MpcdiRegion region = read_region(*region_element, file.profile);
        if (!region_ids.insert(region.id).second)
          fail(*region_element, "<region> id '" + region.id + "' is used twice");
        buffer.regions.push_back(std::move(region));
      }
      file.buffers.push_back(std::move(buffer));
    }
    if (file.buffers.empty()) fail(display, "<display> has no <buffer>");

    if (const XmlElement* files = root.child("files")) {
      for (const XmlElement* fileset : files->children_named("fileset")) {
        const std::string& id = required_attribute(*fileset, "region");
        MpcdiRegion* region = nullptr;
        for (MpcdiBuffer& buffer : file.buffers)
          for (MpcdiRegion& candidate : buffer.regions)
            if (candidate.id == id) region = &candidate;
        if (!region) fail(*fileset, "<fileset> names region '" + id + "', which <display> does not define");
        read_fileset(*fileset, *region, file.profile);
      }
    }
    return file;
  }

 private:
  [[noreturn]] void fail(const XmlElement& element, const std::string& what) const {
    throw std::runtime_error(source_ + ":" + std::to_string(element.line) + ": " + what);
  }

  const std::string& required_attribute(const XmlElement& element, std::string_view name) const {
    const std::string* value = element.attribute(name);
    if (!value) fail(element, "<" + element.name + "> has no attribute '" + std::string(name) + "'");
    return *value;
  }
  const XmlElement& required_child(const XmlElement& element, std::string_view name) const {
    const XmlElement* child = element.child(name);
    if (!child) fail(element, "<" + element.name + "> has no <" + std::string(name) + ">");
    return *child;
  }

  double parse_real(const XmlElement& element, std::string_view what, const std::string& text) const {
    std::string_view trimmed = text;
    while (!trimmed.empty() && std::isspace(static_cast<unsigned char>(trimmed.front()))) trimmed.remove_prefix(1);
    while (!trimmed.empty() && std::isspace(static_cast<unsigned char>(trimmed.back()))) trimmed.remove_suffix(1);
    if (!trimmed.empty() && trimmed.front() == '+') trimmed.remove_prefix(1);
    double value = 0.0;
    const auto [end, error] = std::from_chars(trimmed.data(), trimmed.data() + trimmed.size(), value);
    if (trimmed.empty() || error != std::errc() || end != trimmed.data() + trimmed.size() || !std::isfinite(value))
      fail(element, "<" + element.name + "> " + std::string(what) + " = '" + text + "' is not a finite number");
    return value;
  }
  double real_attribute(const XmlElement& element, std::string_view name, double lo, double hi) const {
    const double value = parse_real(element, "attribute '" + std::string(name) + "'", required_attribute(element, name));
    if (value < lo || value > hi)
      fail(element, "<" + element.name + "> attribute '" + std::string(name) + "' = " + number(value) +
                        ": must be in [" + number(lo) + ", " + number(hi) + "]");
    return value;
  }
  int integer_value(const XmlElement& element, std::string_view what, const std::string& text, int lo, int hi) const {
    const double value = parse_real(element, what, text);
    if (value != std::floor(value) || value < lo || value > hi)
      fail(element, "<" + element.name + "> " + std::string(what) + " = '" + text + "': must be an integer in [" +
                        std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return static_cast<int>(value);
  }
  int optional_resolution(const XmlElement& element, std::string_view name) const {
    const std::string* text = element.attribute(name);
    return text ? integer_value(element, "attribute '" + std::string(name) + "'", *text, 1, kMaxResolutionPx) : 0;
  }
  double child_real(const XmlElement& parent, std::string_view name) const {
    const XmlElement& child = required_child(parent, name);
    return parse_real(child, "value", child.text);
  }
  std::string child_text(const XmlElement& parent, std::string_view name) const {
    const XmlElement& child = required_child(parent, name);
    std::string text = child.text;
    const auto space = [](unsigned char c) { return std::isspace(c) != 0; };
    text.erase(text.begin(), std::find_if_not(text.begin(), text.end(), space));
    text.erase(std::find_if_not(text.rbegin(), text.rend(), space).base(), text.end());
    return text;
  }

  MpcdiRegion read_region(const XmlElement& element, MpcdiProfile profile) const {
    MpcdiRegion region;
    region.id = required_attribute(element, "id");
    region.x = real_attribute(element, "x", 0.0, 1.0);
    region.y = real_attribute(element, "y", 0.0, 1.0);
    region.xsize = real_attribute(element, "xsize", 0.0, 1.0);
    region.ysize = real_attribute(element, "ysize", 0.0, 1.0);
    if (region.xsize <= 0.0 || region.ysize <= 0.0)
      fail(element, "<region> '" + region.id + "' has an empty size (xsize " + number(region.xsize) + ", ysize " +
                        number(region.ysize) + ")");
    region.x_resolution_px = integer_value(element, "attribute 'xResolution'", required_attribute(element, "xResolution"),
                                           1, kMaxResolutionPx);
    region.y_resolution_px = integer_value(element, "attribute 'yResolution'", required_attribute(element, "yResolution"),
                                           1, kMaxResolutionPx);
    if (const XmlElement* frustum = element.child("frustum")) {
      MpcdiFrustum f;
      f.yaw_deg = child_real(*frustum, "yaw");
      f.pitch_deg = child_real(*frustum, "pitch");
      f.roll_deg = child_real(*frustum, "roll");
      f.left_deg = child_real(*frustum, "leftAngle");
      f.right_deg = child_real(*frustum, "rightAngle");
      f.up_deg = child_real(*frustum, "upAngle");
      f.down_deg = child_real(*frustum, "downAngle");
      region.frustum = f;
    } else if (profile == MpcdiProfile::simulation_3d) {
      fail(element, "<region> '" + region.id + "' has no <frustum> (required by the 3d profile)");
    }
    return region;
  }

  /// The archive member a <path> names, relative to mpcdi.xml's folder.
  long long member_for(const XmlElement& element, const std::string& path, const std::string& region_id,
                       const char* what) const {
    std::string member = path;
    std::replace(member.begin(), member.end(), '\\', '/');
    while (member.rfind("./", 0) == 0) member.erase(0, 2);
    long long index = zip_.find(folder_ + member);
    if (index < 0 && !folder_.empty()) index = zip_.find(member);
    if (index < 0)
      fail(element, "region '" + region_id + "': " + what + " '" + path + "' is not in the archive");
    return index;
  }

  void read_fileset(const XmlElement& fileset, MpcdiRegion& region, MpcdiProfile profile) const {
    if (const XmlElement* warp = fileset.child("geometryWarpFile")) {
      MpcdiGeometryWarp result;
      result.path = child_text(*warp, "path");
      const long long index = member_for(*warp, result.path, region.id, "geometry warp file");
      const std::string member_name = zip_.name() + ":" + zip_.names()[static_cast<std::size_t>(index)];
      result.interpolation = warp->child("interpolation") ? child_text(*warp, "interpolation") : "linear";
      WarpInterpolation interpolation = WarpInterpolation::bilinear;
      if (equals_ignoring_case(result.interpolation, "linear")) {
        interpolation = WarpInterpolation::bilinear;
      } else if (equals_ignoring_case(result.interpolation, "cubic") ||
                 equals_ignoring_case(result.interpolation, "bicubic")) {
        interpolation = WarpInterpolation::catmull_rom;
      } else {
        fail(*warp->child("interpolation"), "<interpolation> '" + result.interpolation +
                                                "': must be linear or cubic");
      }
      const bool points_3d = profile == MpcdiProfile::advanced_3d || profile == MpcdiProfile::shader_lamps;
      result.component_depth = points_3d ? 3 : 2;
      if (warp->child("componentDepth"))
        result.component_depth = integer_value(required_child(*warp, "componentDepth"), "value",
                                               child_text(*warp, "componentDepth"), 2, 3);
      result.map = parse_pfm(zip_.read(index), member_name, PfmRowOrder::top_to_bottom);
      if (result.map.channels != 3)
        fail(*warp, "region '" + region.id + "': geometry warp '" + result.path +
                        "' has 1 channel ('Pf'); MPCDI warps have 3 ('PF')");
      if (!points_3d)
        region.warp_mesh = warp_mesh_from_pfm(result.map, member_name, interpolation,
                                              WarpMapConventions{options_.warp_values, WarpVDirection::down});
      region.geometry_warp = std::move(result);
    }
    if (const XmlElement* alpha = fileset.child("alphaMap"))
      region.alpha_map = read_blend_map(*alpha, region.id, "alpha map", true);
    if (const XmlElement* beta = fileset.child("betaMap"))
      region.beta_map = read_blend_map(*beta, region.id, "beta map", false);
  }

  MpcdiBlendMap read_blend_map(const XmlElement& element, const std::string& region_id, const char* what,
                               bool has_gamma) const {
    MpcdiBlendMap map;
    map.path = child_text(element, "path");
    const long long index = member_for(element, map.path, region_id, what);
    if (element.child("componentDepth")) {
      map.component_depth = integer_value(required_child(element, "componentDepth"), "value",
                                          child_text(element, "componentDepth"), 1, 3);
      if (map.component_depth == 2)
        fail(*element.child("componentDepth"), std::string("region '") + region_id + "': " + what +
                                                   " componentDepth 2: must be 1 or 3");
    }
    if (element.child("bitDepth")) {
      map.bit_depth = integer_value(required_child(element, "bitDepth"), "value", child_text(element, "bitDepth"), 8, 16);
      if (map.bit_depth != 8 && map.bit_depth != 16)
        fail(*element.child("bitDepth"), std::string("region '") + region_id + "': " + what + " bitDepth " +
                                             std::to_string(map.bit_depth) + ": must be 8 or 16");
    }
    if (has_gamma && element.child("gammaEmbedded")) {
      map.gamma_embedded = child_real(element, "gammaEmbedded");
      if (!(map.gamma_embedded > 0.0 && map.gamma_embedded <= 10.0))
        fail(*element.child("gammaEmbedded"), std::string("region '") + region_id + "': " + what +
                                                  " gammaEmbedded " + number(map.gamma_embedded) +
                                                  ": must be in (0, 10]");
    }
    map.image = decode_png_map(zip_.read(index), zip_.name() + ":" + zip_.names()[static_cast<std::size_t>(index)]);
    return map;
  }

  const ZipArchive& zip_;
  std::string xml_member_;
  std::string source_;
  MpcdiLoadOptions options_;
  std::string folder_;
};

}  // namespace

const char* to_string(MpcdiProfile profile) {
  switch (profile) {
    case MpcdiProfile::media_2d: return "2d";
    case MpcdiProfile::simulation_3d: return "3d";
    case MpcdiProfile::advanced_3d: return "a3";
    case MpcdiProfile::shader_lamps: return "sl";
  }
  return "?";
}

double MpcdiBlendMap::linear(int x, int y, int c) const {
  return std::pow(static_cast<double>(image.at(x, y, image.channels == 1 ? 0 : c)), gamma_embedded);
}

const MpcdiRegion* MpcdiFile::find_region(const std::string& id) const {
  for (const MpcdiBuffer& buffer : buffers)
    for (const MpcdiRegion& region : buffer.regions)
      if (region.id == id) return &region;
  return nullptr;
}

MpcdiFile load_mpcdi(const std::filesystem::path& path, const MpcdiLoadOptions& options) {
  const ZipArchive zip(path);
  // mpcdi.xml, ignoring case, preferring the shallowest one.
  std::string xml_member;
  std::size_t best_depth = std::numeric_limits<std::size_t>::max();
  for (const std::string& member : zip.names()) {
    if (!equals_ignoring_case(base_name(member), "mpcdi.xml")) continue;
    const auto depth = static_cast<std::size_t>(std::count(member.begin(), member.end(), '/'));
    if (depth < best_depth) best_depth = depth, xml_member = member;
  }
  if (xml_member.empty())
    throw std::runtime_error(zip.name() + ": no mpcdi.xml in the archive (" + std::to_string(zip.names().size()) +
                             " members)");
  return MpcdiReader(zip, xml_member, options).read();
}

}  // namespace zenith::warp
