#pragma once
// The loader's reading of an MPCDI region's colour profile (warp/mpcdi.h):
// the <color> element of a <region> and the .cube LUTs its <fileset> names.
// docs/warp-meshes.md, "Colour profile", lists what is read and refused.
#include <optional>
#include <string>

#include "warp/colour_profile.h"
#include "warp/cube_lut.h"
#include "warp/xml_reader.h"

namespace zenith::warp {

/// A <decodeLUT>, <correctLUT> or <encodeLUT> of a fileset, read.
struct MpcdiColourLut {
  CubeLut lut;
  std::string path;  ///< as the fileset writes it
  int line = 0;      ///< of the element in the descriptor
};
struct MpcdiColourLuts {
  std::optional<MpcdiColourLut> decode, correct, encode;
};

/// The types, gammas and primaries of <color> (VESA MPCDI v2.0 §3.5.2):
/// <decode type="gamma|lut1d|none" gamma>, <correct type="none|lut1d-primary|lut3d">
/// with <primaries> (<redPrimary>, <greenPrimary>, <bluePrimary>, each <red>,
/// <green>, <blue>), <encode type="none|gamma|lut1d|lut3d" gamma>. Throws
/// std::runtime_error "<source>:<line>: region '<id>': <decode> ..." for a
/// missing decode or encode, an unknown type, a gamma missing or outside
/// [kMinColourGamma, kMaxColourGamma], a primaries matrix missing an element
/// or holding a value that is not a finite number.
MpcdiColourProfile read_mpcdi_colour(const XmlElement& color, const std::string& source, const std::string& region_id);

/// Gives `profile` the LUTs its types need and checks them against the file's
/// colour level (1–5, table 3-3; 0: not given, no check): a lut1d decode or
/// encode needs a 1D LUT, a lut3d correct or encode a 3D one; a type above the
/// level is refused ("<correct> type 'lut3d' needs colour level 5; the file
/// says color=\"3\""). A LUT the types do not use is ignored with a warning.
void attach_mpcdi_colour_luts(MpcdiColourProfile& profile, MpcdiColourLuts luts, int colour_level,
                              const std::string& source, const std::string& region_id);

}  // namespace zenith::warp
