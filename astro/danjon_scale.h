#pragma once
// Danjon's luminosity scale of a total lunar eclipse (A. Danjon 1921,
// L'Astronomie 35, 261–265): the Moon near mid-totality as an observer's eye
// rates it, from L = 0 (very dark, the Moon almost invisible) to L = 4 (very
// bright copper-red or orange, the umbra's rim bluish and very bright), in
// tenths between the five descriptions.
//
// The scale is descriptive: no formula turns a magnitude into L. What links
// the two is empirical — observers' L against the Moon's magnitude at
// mid-totality over dozens of eclipses, the correlation H. C. Vital's
// Brazilian observing network (REA) predicts both from. Two of his published
// pairs give its slope: 2008-02-21, predicted L = 3.0 ± 0.4 at m = −2.6 ± 0.4
// (observed 3.0 ± 0.1 and −2.8 ± 0.3), and 2022-11-08, L = 2.4 ± 0.2 from
// m = −1.6 ± 0.4 (geocities.ws/lunissolar2003: Fev08/Report.htm, Nov08.htm):
//   dL/dm = (3.0 − 2.4) / (−2.6 − (−1.6)) = −0.6 per magnitude,
// the scale's five steps over the ~7 magnitudes between the brightest and the
// darkest eclipses. The offset of that line depends on the observers'
// magnitude scale (Vital's −1.6 for 2022 is 0.7 mag fainter than a
// photometer's −2.31 that night), so zenith uses the slope only: the class a
// model implies for an eclipse is the observers' L moved by the model's error
// in brightness at mid-totality.
#include <string_view>

namespace zenith::astro {

/// Danjon's L per magnitude the Moon at mid-totality brightens (above).
inline constexpr double kDanjonPerMagnitude = 0.6;

/// The Danjon class a model implies for an eclipse whose observers rated it
/// `observed_l` and whose Moon at mid-totality fell `measured_drop_mag`
/// magnitudes below the uneclipsed Moon where the model has it fall
/// `model_drop_mag`:
///   L = observed_l + kDanjonPerMagnitude · (measured_drop_mag − model_drop_mag),
/// within the scale's [0, 4]. A model too bright by one magnitude rates its
/// eclipse 0.6 brighter. Throws std::invalid_argument for an `observed_l`
/// outside [0, 4] or a drop that is not finite.
double implied_danjon_class(double observed_l, double measured_drop_mag, double model_drop_mag);

/// The class of Danjon's five nearest `l`: rounded half away from zero,
/// within [0, 4] (0 for NaN).
int nearest_danjon_class(double l);

/// Danjon's description of nearest_danjon_class(l): "very dark: the Moon
/// almost invisible", … "very bright copper-red or orange: the umbra's rim
/// bluish and very bright".
std::string_view danjon_description(double l);

}  // namespace zenith::astro
