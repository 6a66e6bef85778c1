#include "warp/mpcdi_writer.h"

#include <zip.h>

#include <algorithm>
#include <memory>
#include <sstream>
#include <stdexcept>

namespace zenith::warp {
namespace {

bool plain_id(const std::string& id) {
  return !id.empty() && std::all_of(id.begin(), id.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' || c == '_' ||
           c == '.';
  });
}

/// Member names are written as element text: no markup characters.
bool plain_member(const std::string& name) {
  return !name.empty() && name.find_first_of("<>&\"'") == std::string::npos;
}

/// libzip's message for an archive that could not be opened.
std::string zip_open_error(int code) {
  zip_error_t error;
  zip_error_init_with_code(&error, code);
  std::string message = zip_error_strerror(&error);
  zip_error_fini(&error);
  return message;
}

struct ZipDiscard {
  void operator()(zip_t* archive) const {
    if (archive) zip_discard(archive);
  }
};

/// A number in full precision.
std::string number(double value) {
  std::ostringstream text;
  text.precision(17);
  text << value;
  return text.str();
}

/// An <alphaMap> or <betaMap> element of a 1-channel 16-bit PNG member, with
/// `extra` children.
std::string grey16_map_element(const std::string& element, const std::string& member, const std::string& extra) {
  return "      <" + element + ">\n        <path>" + member +
         "</path>\n        <componentDepth>1</componentDepth>\n        <bitDepth>16</bitDepth>\n" + extra + "      </" +
         element + ">\n";
}

/// sl: the region's <frustum> and <coordinateFrame> (the base axes: F = I).
std::string pinhole_elements(const PlanarFrustum& f) {
  std::ostringstream xml;
  xml.precision(17);
  xml << "        <frustum>\n"
      << "          <yaw>" << f.yaw_deg << "</yaw>\n"
      << "          <pitch>" << f.pitch_deg << "</pitch>\n"
      << "          <roll>" << f.roll_deg << "</roll>\n"
      << "          <rightAngle>" << f.right_deg << "</rightAngle>\n"
      << "          <leftAngle>" << f.left_deg << "</leftAngle>\n"
      << "          <upAngle>" << f.up_deg << "</upAngle>\n"
      << "          <downAngle>" << f.down_deg << "</downAngle>\n"
      << "        </frustum>\n"
      << "        <!-- the display's frame: X left, Y up, Z forward; the projector's base axes: pitch (right), "
         "yaw (down), roll (forward) -->\n"
      << "        <coordinateFrame>\n"
      << "          <posx>0</posx><posy>0</posy><posz>0</posz>\n"
      << "          <yawx>0</yawx><yawy>-1</yawy><yawz>0</yawz>\n"
      << "          <pitchx>-1</pitchx><pitchy>0</pitchy><pitchz>0</pitchz>\n"
      << "          <rollx>0</rollx><rolly>0</rolly><rollz>1</rollz>\n"
      << "        </coordinateFrame>\n";
  return xml.str();
}

/// The region's <color> (VESA MPCDI v2.0 §3.5.2: "there shall be a color tag
/// for every region tag"): decode and encode a gamma, no correction; colour level 1 and 2.
std::string colour_element(double gamma) {
  return "        <color>\n          <decode type=\"gamma\" gamma=\"" + number(gamma) +
         "\"/>\n          <correct type=\"none\"/>\n          <encode type=\"gamma\" gamma=\"" + number(gamma) +
         "\"/>\n        </color>\n";
}

}  // namespace

std::string mpcdi_descriptor(const MpcdiRegionExport& r) {
  const bool sl = r.profile == MpcdiProfile::shader_lamps;
  if (!sl && r.profile != MpcdiProfile::media_2d)
    throw std::invalid_argument("MPCDI export: region '" + r.id + "': profile " + to_string(r.profile) +
                                ": only 2d and sl are written");
  if (!plain_id(r.id))
    throw std::invalid_argument("MPCDI export: region id '" + r.id +
                                "': must be letters, digits, '-', '_' or '.' (it is written into XML attributes)");
  const bool warp = !sl || !r.warp_member.empty();
  if (!(r.colour_gamma >= kMinColourGamma && r.colour_gamma <= kMaxColourGamma))
    throw std::invalid_argument("MPCDI export: region '" + r.id + "': colour gamma " + number(r.colour_gamma) +
                                " must be in [" + number(kMinColourGamma) + ", " + number(kMaxColourGamma) + "]");
  if (r.width_px < 1 || r.height_px < 1 || (warp && (r.warp_columns < 1 || r.warp_rows < 1)))
    throw std::invalid_argument("MPCDI export: region '" + r.id + "': resolution and warp size must be at least 1");
  for (const std::string* member : {&r.warp_member, &r.alpha_member, &r.beta_member})
    if ((warp || member != &r.warp_member) && !plain_member(*member))
      throw std::invalid_argument("MPCDI export: region '" + r.id + "': member name '" + *member +
                                  "' is empty or holds XML markup characters");
  std::ostringstream xml;
  xml.precision(17);
  xml << "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
      << "<!-- written by zenith (docs/warp-meshes.md, \"Exporting to warp engines and media servers\") -->\n"
      << (sl ? std::string("<MPCDI profile=\"sl\" geometry=\"") + (warp ? "2" : "1") +
                   "\" color=\"2\" version=\"2.0\">\n"
             : std::string("<MPCDI profile=\"2d\" geometry=\"1\" color=\"1\" version=\"2.0\">\n"))
      << "  <display>\n"
      << "    <buffer id=\"" << r.id << "\" xResolution=\"" << r.width_px << "\" yResolution=\"" << r.height_px
      << "\">\n"
      << "      <region id=\"" << r.id << "\" x=\"0\" y=\"0\" xsize=\"1\" ysize=\"1\" xResolution=\"" << r.width_px
      << "\" yResolution=\"" << r.height_px << "\">\n"
      << (sl ? pinhole_elements(r.frustum) : std::string()) << colour_element(r.colour_gamma) << "      </region>\n"
      << "    </buffer>\n"
      << "  </display>\n"
      << "  <files>\n"
      << "    <fileset region=\"" << r.id << "\">\n";
  if (sl && warp) {
    xml << "      <distortionMap>\n"
        << "        <path>" << r.warp_member << "</path>\n"
        << "      </distortionMap>\n";
  } else if (!sl) {
    xml << "      <geometryWarpFile>\n"
        << "        <path>" << r.warp_member << "</path>\n"
        << "        <interpolation>" << (r.interpolation == WarpInterpolation::bilinear ? "linear" : "cubic")
        << "</interpolation>\n"
        << "        <componentDepth>2</componentDepth>\n"
        << "        <bitDepth>32</bitDepth>\n"
        << "        <xSamples>" << r.warp_columns << "</xSamples>\n"
        << "        <ySamples>" << r.warp_rows << "</ySamples>\n"
        << "        <originOf2DData>topLeftCorner</originOf2DData>\n"
        << "      </geometryWarpFile>\n";
  }
  xml << grey16_map_element("alphaMap", r.alpha_member,
                            "        <gammaEmbedded>" + number(r.alpha_gamma_embedded) + "</gammaEmbedded>\n")
      << grey16_map_element("betaMap", r.beta_member, "") << "    </fileset>\n"
      << "  </files>\n"
      << "</MPCDI>\n";
  return xml.str();
}

void write_mpcdi_archive(const std::filesystem::path& path, const std::string& descriptor,
                         const std::vector<std::pair<std::string, std::filesystem::path>>& members) {
  const std::string name = path.string();
  int code = 0;
  std::unique_ptr<zip_t, ZipDiscard> archive(zip_open(name.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &code));
  if (!archive) throw std::runtime_error(name + ": cannot create the MPCDI archive (" + zip_open_error(code) + ")");
  const auto add = [&](const std::string& member, zip_source_t* source, const std::string& what) {
    if (source == nullptr)
      throw std::runtime_error(name + ": cannot add " + what + " (" + zip_strerror(archive.get()) + ")");
    const zip_int64_t index = zip_file_add(archive.get(), member.c_str(), source, ZIP_FL_OVERWRITE | ZIP_FL_ENC_UTF_8);
    if (index < 0) {
      zip_source_free(source);
      throw std::runtime_error(name + ": cannot add " + what + " (" + zip_strerror(archive.get()) + ")");
    }
    // Deflate at its fastest level: a 1920 x 1200 output's warp is 110 MB of
    // floats, which the default level takes several times longer to pack.
    if (zip_set_file_compression(archive.get(), static_cast<zip_uint64_t>(index), ZIP_CM_DEFLATE, 1) != 0)
      throw std::runtime_error(name + ": cannot set the compression of " + what + " (" + zip_strerror(archive.get()) +
                               ")");
  };
  // The descriptor's bytes must outlive zip_close: libzip reads sources then.
  add("mpcdi.xml", zip_source_buffer(archive.get(), descriptor.data(), descriptor.size(), 0), "mpcdi.xml");
  for (const auto& [member, file] : members)
    add(member, zip_source_file(archive.get(), file.c_str(), 0, 0), "member '" + member + "' from " + file.string());
  if (zip_close(archive.get()) != 0)
    throw std::runtime_error(name + ": cannot write the MPCDI archive (" + zip_strerror(archive.get()) + ")");
  archive.release();  // zip_close freed it
}

}  // namespace zenith::warp
