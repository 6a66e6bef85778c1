#include "warp/mpcdi.h"

#include <zip.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <span>
#include <stdexcept>
#include <utility>

#include <glm/geometric.hpp>

#include <spdlog/spdlog.h>

#include "core/strings.h"
#include "warp/mpcdi_colour.h"
#include "warp/orientation_angles.h"
#include "warp/xml_reader.h"

namespace zenith::warp {
namespace {

constexpr zip_uint64_t kMaxMemberBytes = zip_uint64_t{1} << 30;  // 1 GiB: far past any warp or blend file
constexpr int kMaxResolutionPx = 65536;
constexpr double kMaxEdgeDeg = 90.0;        // a frustum's edge angles, open: a plane cannot reach 90°
constexpr double kFrameTolerance = 1e-3;    // a coordinate frame's axes: unit and orthogonal within this
constexpr std::size_t kListedMembers = 12;  // members named in the "no mpcdi.xml" message
// The values of <geometricUnit> and <originOf3DData> (VESA MPCDI v2.0 §3.5.2).
constexpr std::array<std::string_view, 8> kGeometricUnits = {"mm", "cm", "dm", "m", "in", "ft", "yd", "unknown"};
constexpr std::array<std::string_view, 4> kOrigins = {"centerOfMass", "idealEyePoint", "floorCenter", "unknown"};

std::string number(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

/// Whether the file begins with a ZIP local file header ("PK\3\4").
bool starts_like_a_zip(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  char magic[4] = {};
  return in.read(magic, 4) && magic[0] == 'P' && magic[1] == 'K' && magic[2] == 3 && magic[3] == 4;
}

std::uintmax_t file_size_or_zero(const std::filesystem::path& path) {
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  return error ? 0 : size;
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
      std::string hint;
      if ((code == ZIP_ER_NOZIP || code == ZIP_ER_INCONS) && starts_like_a_zip(path))
        hint =
            ": it starts like one, so it may be truncated (the directory at the end of a ZIP is missing or "
            "damaged; " +
            std::to_string(file_size_or_zero(path)) + " bytes; copy or download it again)";
      throw std::runtime_error(name_ + ": cannot open as a ZIP archive (" + reason + ")" + hint);
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
    std::unique_ptr<zip_file_t, int (*)(zip_file_t*)> file(
        zip_fopen_index(archive_, static_cast<zip_uint64_t>(index), 0), zip_fclose);
    if (!file) throw std::runtime_error(name_ + ":" + member + ": cannot read (" + zip_strerror(archive_) + ")");
    std::string bytes(stat.size, '\0');
    zip_uint64_t done = 0;
    while (done < stat.size) {
      const zip_int64_t got = zip_fread(file.get(), bytes.data() + done, stat.size - done);
      if (got < 0)
        throw std::runtime_error(name_ + ":" + member + ": corrupt (" + zip_file_strerror(file.get()) +
                                 "): the archive may be truncated or damaged");
      if (got == 0) break;
      done += static_cast<zip_uint64_t>(got);
    }
    if (done != stat.size)
      throw std::runtime_error(name_ + ":" + member + ": " + std::to_string(done) + " of " + std::to_string(stat.size) +
                               " bytes: the archive may be truncated");
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
    file.descriptor = xml_member_;
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
    if (const std::string* level = root.attribute("color")) file.colour_level = colour_level(root, *level);

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

    std::map<std::string, MpcdiColourLuts> colour_luts;  // by region id
    if (const XmlElement* files = root.child("files")) {
      for (const XmlElement* fileset : files->children_named("fileset")) {
        const std::string& id = required_attribute(*fileset, "region");
        MpcdiRegion* region = nullptr;
        for (MpcdiBuffer& buffer : file.buffers)
          for (MpcdiRegion& candidate : buffer.regions)
            if (candidate.id == id) region = &candidate;
        if (!region) fail(*fileset, "<fileset> names region '" + id + "', which <display> does not define");
        read_fileset(*fileset, *region, file.profile);
        read_colour_luts(*fileset, region->id, colour_luts[region->id]);
      }
    }
    // The colour profile: <color> with the fileset's LUTs; without <color>, the identity.
    for (MpcdiBuffer& buffer : file.buffers)
      for (MpcdiRegion& region : buffer.regions) {
        MpcdiColourLuts& luts = colour_luts[region.id];
        if (region.colour) {
          attach_mpcdi_colour_luts(*region.colour, std::move(luts), file.colour_level, source_, region.id);
        } else if (luts.decode || luts.correct || luts.encode) {
          spdlog::warn(
              "{}:{}: region '{}' has colour LUTs in its <fileset> but no <color> element to use them: ignored",
              source_, region.line, region.id);
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
    const std::optional<double> value = finite_number(text);
    if (!value)
      fail(element, "<" + element.name + "> " + std::string(what) + " = '" + text + "' is not a finite number");
    return *value;
  }
  double real_attribute(const XmlElement& element, std::string_view name, double lo, double hi) const {
    const double value =
        parse_real(element, "attribute '" + std::string(name) + "'", required_attribute(element, name));
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
  /// <MPCDI color="..">: the colour level, 1..5 (VESA MPCDI v2.0 table 3-3),
  /// which bounds the stage types a <color> may use. Evans & Sutherland's
  /// Digistar writes color="TBD": text that is no number (or is empty) reads
  /// as "no level given" (0, nothing checked against it, no profile assumed),
  /// with one warning; a number outside the table stays an error.
  int colour_level(const XmlElement& root, const std::string& text) const {
    if (!finite_number(text)) {
      spdlog::warn(
          "{}:{}: <MPCDI> attribute 'color' = '{}' is not a colour level (an integer in [1, 5], VESA MPCDI "
          "v2.0 table 3-3): read as no colour level given",
          source_, root.line, text);
      return 0;
    }
    return integer_value(root, "attribute 'color' (the colour level, table 3-3)", text, 1, 5);
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
    return std::string(trimmed(required_child(parent, name).text));
  }

  /// <yaw>, <pitch> or <roll> of a <frustum>: degrees in [−360, 360] (vendors
  /// write [0, 360) as often as (−180, 180]); normalized by the caller.
  double orientation_angle(const XmlElement& frustum, std::string_view name, const std::string& region_id) const {
    const double value = region_real(frustum, name, region_id);
    if (value < -kMaxOrientationDeg || value > kMaxOrientationDeg)
      fail(*frustum.child(name), "region '" + region_id + "': <frustum> <" + frustum.child(name)->name +
                                     "> = " + number(value) + ": must be in [" + number(-kMaxOrientationDeg) + ", " +
                                     number(kMaxOrientationDeg) + "] degrees ([0, 360) and (-180, 180] both read)");
    return value;
  }

  /// The number in the child `name` of a region's <frustum> or
  /// <coordinateFrame>; the errors name the region.
  double region_real(const XmlElement& parent, std::string_view name, const std::string& region_id) const {
    const XmlElement* child = parent.child(name);
    if (!child) fail(parent, "region '" + region_id + "': <" + parent.name + "> has no <" + std::string(name) + ">");
    const std::optional<double> value = finite_number(child->text);
    if (!value)
      fail(*child, "region '" + region_id + "': <" + parent.name + "> <" + child->name + "> = '" + child->text +
                       "' is not a finite number");
    return *value;
  }

  MpcdiRegion read_region(const XmlElement& element, MpcdiProfile profile) const {
    MpcdiRegion region;
    region.id = required_attribute(element, "id");
    region.line = element.line;
    region.x = real_attribute(element, "x", 0.0, 1.0);
    region.y = real_attribute(element, "y", 0.0, 1.0);
    region.xsize = real_attribute(element, "xsize", 0.0, 1.0);
    region.ysize = real_attribute(element, "ysize", 0.0, 1.0);
    if (region.xsize <= 0.0 || region.ysize <= 0.0)
      fail(element, "<region> '" + region.id + "' has an empty size (xsize " + number(region.xsize) + ", ysize " +
                        number(region.ysize) + ")");
    region.x_resolution_px = integer_value(element, "attribute 'xResolution'",
                                           required_attribute(element, "xResolution"), 1, kMaxResolutionPx);
    region.y_resolution_px = integer_value(element, "attribute 'yResolution'",
                                           required_attribute(element, "yResolution"), 1, kMaxResolutionPx);
    const bool needs_frustum = profile == MpcdiProfile::simulation_3d || profile == MpcdiProfile::shader_lamps;
    if (const XmlElement* frustum = element.child("frustum")) {
      region.frustum = read_frustum(*frustum, region.id);
    } else if (needs_frustum) {
      fail(element,
           "<region> '" + region.id + "' has no <frustum> (required by the " + to_string(profile) + " profile)");
    }
    // The 2d and a3 profiles have no coordinate frame (VESA MPCDI v2.0 §3.5.2):
    // one there is skipped, as before this was read at all.
    if (const XmlElement* frame = element.child("coordinateFrame"); frame && needs_frustum) {
      region.coordinate_frame = read_coordinate_frame(*frame, region.id);
    } else if (profile == MpcdiProfile::shader_lamps) {
      fail(element, "<region> '" + region.id +
                        "' has no <coordinateFrame> (required by the sl profile: the "
                        "projector's position and axes)");
    }
    if (const XmlElement* color = element.child("color")) region.colour = read_mpcdi_colour(*color, source_, region.id);
    return region;
  }

  /// The fileset's <decodeLUT>, <correctLUT> and <encodeLUT>: .cube files
  /// (§3.8) with an <interpolation> hint (linear, smooth or unknown; every LUT
  /// is interpolated linearly, 1D, or trilinearly, 3D: §3.8 leaves the hint optional).
  void read_colour_luts(const XmlElement& fileset, const std::string& region_id, MpcdiColourLuts& luts) const {
    const auto read = [&](const char* name, std::optional<MpcdiColourLut>& out) {
      const XmlElement* element = fileset.child(name);
      if (!element || names_no_file(*element, region_id)) return;
      MpcdiColourLut lut;
      lut.line = element->line;
      lut.path = child_text(*element, "path");
      if (const XmlElement* interpolation = element->child("interpolation")) {
        const std::string hint(trimmed(interpolation->text));
        if (!equals_ignoring_case(hint, "linear") && !equals_ignoring_case(hint, "smooth") &&
            !equals_ignoring_case(hint, "unknown"))
          fail(*interpolation,
               "region '" + region_id + "': <" + element->name + "> <interpolation> '" + hint +
                   "': must be linear, smooth or unknown (keystone is meaningless for colour, §2.5.1.2)");
      }
      const long long index = member_for(*element, lut.path, region_id, name);
      lut.lut = parse_cube_lut(zip_.read(index), zip_.name() + ":" + zip_.names()[static_cast<std::size_t>(index)]);
      out = std::move(lut);
    };
    read("decodeLUT", luts.decode);
    read("correctLUT", luts.correct);
    read("encodeLUT", luts.encode);
  }

  /// <frustum>: yaw, pitch, roll in [−360, 360] (normalized), the edge angles
  /// in (−90, 90) with left < right and down < up (VESA MPCDI v2.0 table 2-1).
  MpcdiFrustum read_frustum(const XmlElement& frustum, const std::string& region_id) const {
    MpcdiFrustum f;
    f.line = frustum.line;
    const YawPitchRollDeg orientation = normalized_yaw_pitch_roll({orientation_angle(frustum, "yaw", region_id),
                                                                   orientation_angle(frustum, "pitch", region_id),
                                                                   orientation_angle(frustum, "roll", region_id)});
    f.yaw_deg = orientation.yaw_deg;
    f.pitch_deg = orientation.pitch_deg;
    f.roll_deg = orientation.roll_deg;
    const auto edge = [&](std::string_view name) {
      const double value = region_real(frustum, name, region_id);
      if (!(value > -kMaxEdgeDeg && value < kMaxEdgeDeg))
        fail(*frustum.child(name), "region '" + region_id + "': <frustum> <" + frustum.child(name)->name +
                                       "> = " + number(value) + ": must be in (-90, 90) degrees");
      return value;
    };
    f.left_deg = edge("leftAngle");
    f.right_deg = edge("rightAngle");
    f.up_deg = edge("upAngle");
    f.down_deg = edge("downAngle");
    if (!(f.left_deg < f.right_deg))
      fail(frustum, "region '" + region_id + "': <frustum> <leftAngle> = " + number(f.left_deg) +
                        " must be less than <rightAngle> = " + number(f.right_deg));
    if (!(f.down_deg < f.up_deg))
      fail(frustum, "region '" + region_id + "': <frustum> <downAngle> = " + number(f.down_deg) +
                        " must be less than <upAngle> = " + number(f.up_deg));
    return f;
  }

  /// <coordinateFrame>: posx .. rollz, all twelve required; the yaw, pitch and
  /// roll vectors orthonormal and right-handed (pitch × yaw = roll) within 1e-3
  /// (VESA MPCDI v2.0 §2.2.2, "orthonormal unit vectors").
  MpcdiCoordinateFrame read_coordinate_frame(const XmlElement& frame, const std::string& region_id) const {
    MpcdiCoordinateFrame f;
    f.line = frame.line;
    const auto vector = [&](const char* stem) {
      const std::string s = stem;
      return glm::dvec3(region_real(frame, s + "x", region_id), region_real(frame, s + "y", region_id),
                        region_real(frame, s + "z", region_id));
    };
    f.position = vector("pos");
    f.yaw_axis = vector("yaw");
    f.pitch_axis = vector("pitch");
    f.roll_axis = vector("roll");
    const auto text = [](const glm::dvec3& v) {
      return "(" + number(v.x) + ", " + number(v.y) + ", " + number(v.z) + ")";
    };
    const std::string where = "region '" + region_id + "': <coordinateFrame> ";
    for (const auto& [name, axis] : {std::pair{"yaw", f.yaw_axis}, {"pitch", f.pitch_axis}, {"roll", f.roll_axis}})
      if (std::abs(glm::length(axis) - 1.0) > kFrameTolerance)
        fail(frame, where + "<" + name + "x>..<" + name + "z> = " + text(axis) + " has length " +
                        number(glm::length(axis)) + ": the yaw, pitch and roll vectors must be unit vectors (within " +
                        number(kFrameTolerance) + ")");
    const double yaw_pitch = glm::dot(f.yaw_axis, f.pitch_axis), pitch_roll = glm::dot(f.pitch_axis, f.roll_axis),
                 roll_yaw = glm::dot(f.roll_axis, f.yaw_axis);
    if (std::max({std::abs(yaw_pitch), std::abs(pitch_roll), std::abs(roll_yaw)}) > kFrameTolerance)
      fail(frame, where + "the yaw " + text(f.yaw_axis) + ", pitch " + text(f.pitch_axis) + " and roll " +
                      text(f.roll_axis) + " vectors are not orthogonal (dot products " + number(yaw_pitch) + ", " +
                      number(pitch_roll) + ", " + number(roll_yaw) + ")");
    if (glm::dot(glm::cross(f.pitch_axis, f.yaw_axis), f.roll_axis) < 0.0)
      fail(frame, where + "the pitch " + text(f.pitch_axis) + ", yaw " + text(f.yaw_axis) + " and roll " +
                      text(f.roll_axis) +
                      " vectors form a left-handed frame (pitch x yaw = -roll); MPCDI's is "
                      "right-handed: pitch to the right, yaw down, roll forward (VESA MPCDI v2.0 section 2.2)");
    return f;
  }

  /// The archive member a <path> names, relative to mpcdi.xml's folder.
  long long member_for(const XmlElement& element, const std::string& path, const std::string& region_id,
                       const char* what) const {
    std::string member = path;
    std::replace(member.begin(), member.end(), '\\', '/');
    while (member.rfind("./", 0) == 0) member.erase(0, 2);
    long long index = zip_.find(folder_ + member);
    if (index < 0 && !folder_.empty()) index = zip_.find(member);
    if (index < 0) fail(element, "region '" + region_id + "': " + what + " '" + path + "' is not in the archive");
    return index;
  }

  /// Whether a <geometryWarpFile>, <alphaMap> or <betaMap> names no file: an
  /// empty element (`<alphaMap />`) or an empty <path>. Vendors write these
  /// for "none"; logged as a warning and ignored.
  bool names_no_file(const XmlElement& element, const std::string& region_id) const {
    const XmlElement* path = element.child("path");
    const bool empty_element = element.children.empty() && trimmed(element.text).empty();
    if (!empty_element && !(path && trimmed(path->text).empty())) return false;
    spdlog::warn("{}:{}: region '{}': <{}> names no file ({}): ignored", source_, element.line, region_id, element.name,
                 empty_element ? "an empty element" : "an empty <path>");
    return true;
  }

  void read_fileset(const XmlElement& fileset, MpcdiRegion& region, MpcdiProfile profile) const {
    const XmlElement* warp = fileset.child("geometryWarpFile");
    if (warp && !names_no_file(*warp, region.id)) {
      MpcdiGeometryWarp result;
      result.path = child_text(*warp, "path");
      const long long index = member_for(*warp, result.path, region.id, "geometry warp file");
      const std::string member_name = zip_.name() + ":" + zip_.names()[static_cast<std::size_t>(index)];
      result.interpolation = warp->child("interpolation") ? child_text(*warp, "interpolation") : "linear";
      // VESA MPCDI v2.0 §2.7: linear, keystone, smooth (a curved scheme such
      // as bicubic), unknown; "cubic" and "bicubic" as some writers put it.
      WarpInterpolation interpolation = WarpInterpolation::bilinear;
      if (equals_ignoring_case(result.interpolation, "linear") ||
          equals_ignoring_case(result.interpolation, "unknown")) {
        interpolation = WarpInterpolation::bilinear;
      } else if (equals_ignoring_case(result.interpolation, "cubic") ||
                 equals_ignoring_case(result.interpolation, "bicubic") ||
                 equals_ignoring_case(result.interpolation, "smooth")) {
        interpolation = WarpInterpolation::catmull_rom;
      } else {
        fail(*warp->child("interpolation"),
             "region '" + region.id + "': <interpolation> '" + result.interpolation +
                 "': must be linear, cubic (smooth, bicubic) or unknown (read as linear)");
      }
      result.mesh_interpolation = interpolation;
      result.line = warp->line;
      const bool profile_3d_points = profile == MpcdiProfile::advanced_3d || profile == MpcdiProfile::shader_lamps;
      result.component_depth = profile_3d_points ? 3 : 2;
      if (warp->child("componentDepth"))
        result.component_depth =
            integer_value(required_child(*warp, "componentDepth"), "value", child_text(*warp, "componentDepth"), 2, 3);
      if (warp->child("geometricUnit"))
        result.geometric_unit = one_of(*warp->child("geometricUnit"), region.id, kGeometricUnits);
      if (warp->child("originOf3DData"))
        result.origin_of_3d_data = one_of(*warp->child("originOf3DData"), region.id, kOrigins);
      // The 3d profile's warps are 2D, but media servers write 3D points there
      // too; they say so with the 3D elements (VESA MPCDI v2.0 §3.5.2).
      result.points_3d =
          profile_3d_points ||
          (profile == MpcdiProfile::simulation_3d &&
           (result.component_depth == 3 || warp->child("geometricUnit") || warp->child("originOf3DData")));
      result.map = parse_pfm(zip_.read(index), member_name, PfmRowOrder::top_to_bottom);
      if (result.map.channels != 3)
        fail(*warp, "region '" + region.id + "': geometry warp '" + result.path +
                        "' has 1 channel ('Pf'); MPCDI warps have 3 ('PF')");
      if (result.points_3d) {
        check_point_map(*warp, region.id, result);
      } else {
        region.warp_mesh = warp_mesh_from_pfm(result.map, member_name, interpolation,
                                              WarpMapConventions{options_.warp_values, WarpVDirection::down});
      }
      region.geometry_warp = std::move(result);
    }
    // sl: the lens distortion LUT, a 2D warp of the pinhole's image (§2.6, §3.9).
    const XmlElement* distortion = fileset.child("distortionMap");
    if (distortion && profile == MpcdiProfile::shader_lamps && !names_no_file(*distortion, region.id)) {
      MpcdiGeometryWarp result;
      result.line = distortion->line;
      result.path = child_text(*distortion, "path");
      result.interpolation = "linear";
      result.mesh_interpolation = WarpInterpolation::bilinear;
      const long long index = member_for(*distortion, result.path, region.id, "distortion map");
      const std::string member_name = zip_.name() + ":" + zip_.names()[static_cast<std::size_t>(index)];
      result.map = parse_pfm(zip_.read(index), member_name, PfmRowOrder::top_to_bottom);
      if (result.map.channels != 3)
        fail(*distortion, "region '" + region.id + "': distortion map '" + result.path +
                              "' has 1 channel ('Pf'); MPCDI distortion maps have 3 ('PF'), as 2D warps");
      region.distortion_mesh = warp_mesh_from_pfm(result.map, member_name, WarpInterpolation::bilinear,
                                                  WarpMapConventions{WarpValues::absolute, WarpVDirection::down});
      region.distortion_map = std::move(result);
    }
    const XmlElement* alpha = fileset.child("alphaMap");
    if (alpha && !names_no_file(*alpha, region.id))
      region.alpha_map = read_blend_map(*alpha, region.id, "alpha map", true);
    const XmlElement* beta = fileset.child("betaMap");
    if (beta && !names_no_file(*beta, region.id)) region.beta_map = read_blend_map(*beta, region.id, "beta map", false);
  }

  /// The element's text, one of `allowed` (ignoring case), as the list spells it.
  std::string one_of(const XmlElement& element, const std::string& region_id,
                     std::span<const std::string_view> allowed) const {
    const std::string value(trimmed(element.text));
    std::string list;
    for (const std::string_view a : allowed) {
      if (equals_ignoring_case(value, a)) return std::string(a);
      list += (list.empty() ? "" : ", ") + std::string(a);
    }
    fail(element, "region '" + region_id + "': <" + element.name + "> '" + value + "': must be one of " + list);
  }

  /// A 3D point map: at least 2 × 2 samples (VESA MPCDI v2.0 §3.6) and one finite point.
  void check_point_map(const XmlElement& warp, const std::string& region_id, const MpcdiGeometryWarp& result) const {
    const PfmImage& map = result.map;
    if (map.width < 2 || map.height < 2)
      fail(warp, "region '" + region_id + "': 3D geometry warp '" + result.path + "' has " + std::to_string(map.width) +
                     " x " + std::to_string(map.height) + " samples: at least 2 x 2 are needed");
    for (int y = 0; y < map.height; ++y)
      for (int x = 0; x < map.width; ++x)
        if (std::isfinite(map.at(x, y, 0)) && std::isfinite(map.at(x, y, 1)) && std::isfinite(map.at(x, y, 2))) return;
    fail(warp,
         "region '" + region_id + "': 3D geometry warp '" + result.path + "' has no valid point (every sample NaN)");
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
        fail(*element.child("componentDepth"),
             std::string("region '") + region_id + "': " + what + " componentDepth 2: must be 1 or 3");
    }
    if (element.child("bitDepth")) {
      map.bit_depth =
          integer_value(required_child(element, "bitDepth"), "value", child_text(element, "bitDepth"), 8, 16);
      if (map.bit_depth != 8 && map.bit_depth != 16)
        fail(*element.child("bitDepth"), std::string("region '") + region_id + "': " + what + " bitDepth " +
                                             std::to_string(map.bit_depth) + ": must be 8 or 16");
    }
    if (has_gamma && element.child("gammaEmbedded")) {
      map.gamma_embedded = child_real(element, "gammaEmbedded");
      if (!(map.gamma_embedded > 0.0 && map.gamma_embedded <= 10.0))
        fail(*element.child("gammaEmbedded"), std::string("region '") + region_id + "': " + what + " gammaEmbedded " +
                                                  number(map.gamma_embedded) + ": must be in (0, 10]");
    }
    map.image = decode_png_map(zip_.read(index), zip_.name() + ":" + zip_.names()[static_cast<std::size_t>(index)]);
    map.line = element.line;
    // VESA MPCDI v2.0 §3.7: "Blend maps must be a minimum of 2x2 pixels"; the
    // declared depths describe the PNG (§3.6.1, table of <alphaMap> and <betaMap>).
    const std::string named = std::string("region '") + region_id + "': " + what + " '" + map.path + "'";
    if (map.image.width < 2 || map.image.height < 2)
      fail(element, core::cat(named, " is ", map.image.width, "x", map.image.height,
                              " px: MPCDI blend maps must be at least 2x2 px (VESA MPCDI v2.0 §3.7)"));
    if (!element.child("componentDepth")) map.component_depth = map.image.channels;
    if (!element.child("bitDepth")) map.bit_depth = map.image.bit_depth;
    if (map.component_depth != map.image.channels)
      fail(*element.child("componentDepth"),
           core::cat(named, " declares componentDepth ", map.component_depth, ", and its PNG has ", map.image.channels,
                     map.image.channels == 1 ? " channel (grey)" : " channels (RGB)"));
    if (map.bit_depth != map.image.bit_depth)
      fail(*element.child("bitDepth"), core::cat(named, " declares bitDepth ", map.bit_depth, ", and its PNG has ",
                                                 map.image.bit_depth, " bits a channel"));
    return map;
  }

  const ZipArchive& zip_;
  std::string xml_member_;
  std::string source_;
  MpcdiLoadOptions options_;
  std::string folder_;
};

/// A member that is the debris of an archiver, not content (macOS resource forks).
bool is_archiver_debris(const std::string& member) {
  return member.rfind("__MACOSX/", 0) == 0 || base_name(member).substr(0, 2) == "._";
}

/// The shallowest member whose base name is `name` (ignoring case); "" when none.
std::string shallowest_named(const ZipArchive& zip, std::string_view name) {
  std::string found;
  std::size_t best_depth = std::numeric_limits<std::size_t>::max();
  for (const std::string& member : zip.names()) {
    if (is_archiver_debris(member) || !equals_ignoring_case(base_name(member), name)) continue;
    const auto depth = static_cast<std::size_t>(std::count(member.begin(), member.end(), '/'));
    if (depth < best_depth) best_depth = depth, found = member;
  }
  return found;
}

/// "'a', 'b', 'c'", at most kListedMembers of them, then "and N more".
std::string listed(const std::vector<std::string>& members) {
  std::string text;
  for (std::size_t k = 0; k < members.size() && k < kListedMembers; ++k)
    text += (k == 0 ? "'" : ", '") + members[k] + "'";
  if (members.size() > kListedMembers) text += " and " + std::to_string(members.size() - kListedMembers) + " more";
  return text.empty() ? "none" : text;
}

/// The member holding the descriptor: mpcdi.xml (VESA; in any folder, the
/// shallowest, ignoring case), else mpacs.xml, else the archive's only .xml
/// member (older Evans & Sutherland exports name it after the show). Throws
/// naming the archive's members when there is none or more than one candidate.
std::string descriptor_member(const ZipArchive& zip) {
  std::string member = shallowest_named(zip, "mpcdi.xml");
  if (!member.empty()) return member;
  member = shallowest_named(zip, "mpacs.xml");
  if (member.empty()) {
    std::vector<std::string> xml;
    for (const std::string& name : zip.names()) {
      const std::string_view base = base_name(name);
      if (!is_archiver_debris(name) && base.size() > 4 && equals_ignoring_case(base.substr(base.size() - 4), ".xml"))
        xml.push_back(name);
    }
    if (xml.size() != 1)
      throw std::runtime_error(zip.name() + ": no mpcdi.xml in the archive; its " + std::to_string(zip.names().size()) +
                               " members: " + listed(zip.names()) +
                               (xml.empty() ? std::string(" (no .xml member to read instead)")
                                            : " (" + std::to_string(xml.size()) +
                                                  " .xml members: cannot tell which one is the descriptor)"));
    member = xml.front();
  }
  spdlog::info("{}: no mpcdi.xml; reading '{}' as the MPCDI descriptor", zip.name(), member);
  return member;
}

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
  return MpcdiReader(zip, descriptor_member(zip), options).read();
}

}  // namespace zenith::warp
