#pragma once
// Whether the eye sees a star against the sky: Schaefer's relation between the
// sky's brightness and the faintest star seen (docs/night-sky.md, "Visibility").
//
// Schaefer (1990, PASP 102, 212, eq. 2–3; also Schaefer 1993, Vistas in
// Astronomy 36, 311): the threshold illuminance of a point source against a
// background of surface brightness B [nanolamberts] is
//   I = C (1 + √(K B))²   [foot-candles],
// scotopic (B < 1479 nL): C = 10^−9.80, K = 10^−1.90;
// photopic:               C = 10^−8.35, K = 10^−5.90;
// and a star of V magnitude m gives I = 10^(−0.4 (m + 16.57)) ft-cd, so the
// limiting magnitude is m = −16.57 − 2.5 log10 I. With Garstang's (1986, PASP
// 98, 364) conversion B = 34.08 exp(20.7233 − 0.92104 μ_V) nL, a dark zenith of
// 22.0 mag/arcsec² gives 6.6 (the eye's textbook ~6.5). No corrections for age,
// experience, pupil or seeing (Schaefer's F factors) are applied: a typical
// observer, both eyes, dark-adapted.
namespace zenith::validate {

/// Garstang's surface brightness in nanolamberts of a V surface brightness [mag/arcsec²].
double nanolamberts_from_v_mag_arcsec2(double mag_per_arcsec2);
/// Schaefer's naked-eye limiting V magnitude against a sky of `sky_v_mag_arcsec2`.
double naked_eye_limiting_magnitude(double sky_v_mag_arcsec2);

}  // namespace zenith::validate
