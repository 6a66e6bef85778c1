#pragma once
// Instants for the ephemerides: an ISO 8601 UTC time ("2026-12-21T16:30:00Z")
// and its Julian dates in UTC, TT and UT1 (ERFA, the IAU SOFA algorithms).
//
//   TT  = TAI + 32.184 s, TAI = UTC + leap seconds (eraDat: the table ERFA
//         2.0 ships, 37 s since 2017; no leap second has been added since, and
//         ERFA reports dates beyond its release + 5 years as "dubious" but
//         still answers with the last value, which we accept).
//   UT1 = UTC + ΔUT1. ΔUT1 is kept within ±0.9 s by the leap seconds and is
//         only known from IERS bulletins, so by default we take ΔUT1 = 0: at
//         most 0.9 s of Earth rotation, 13.5″ of hour angle, far inside the
//         checks' 1′ (docs/night-sky.md). Callers with a bulletin may pass it.
// Julian dates are two-part (day1 + day2) for full double precision.
#include <string>

namespace zenith::astro {

struct UtcTime {
  int year = 2000, month = 1, day = 1, hour = 12, minute = 0;
  double second = 0.0;
};

/// Parses "YYYY-MM-DDThh:mm[:ss[.fff]]" followed by "Z" or "+00:00" (UTC only;
/// a space may replace the T). Throws std::invalid_argument saying what is
/// wrong (format, month 13, second 61, a time zone other than UTC, ...).
UtcTime parse_utc_time(const std::string& text);

/// "YYYY-MM-DDThh:mm:ss.sssZ".
std::string format_utc_time(const UtcTime& time);

struct JulianDate {
  double day1 = 0.0, day2 = 0.0;
  double value() const { return day1 + day2; }
};

class AstroTime {
 public:
  /// Throws std::invalid_argument for a date ERFA cannot convert (before 1960
  /// has no UTC, or an impossible calendar date) or |ΔUT1| > 0.9 s.
  static AstroTime from_utc(const UtcTime& utc, double dut1_s = 0.0);
  /// From a Terrestrial Time Julian date (e.g. an almanac's "0h TD").
  static AstroTime from_tt(double tt_julian_date, double dut1_s = 0.0);

  /// This instant moved by `seconds` of UTC (a leap second inside the shift is
  /// not counted: UTC quasi-Julian-date arithmetic, as ERFA defines it).
  AstroTime plus_seconds(double seconds) const;

  const JulianDate& utc() const { return utc_; }
  const JulianDate& tt() const { return tt_; }
  const JulianDate& ut1() const { return ut1_; }
  double dut1_s() const { return dut1_s_; }
  /// Julian years of TT since J2000.0 (proper motion).
  double julian_years_since_j2000() const;
  /// The calendar UTC time (rounded to the microsecond).
  UtcTime calendar_utc() const;

 private:
  static AstroTime from_utc_julian(JulianDate utc, double dut1_s);
  JulianDate utc_, tt_, ut1_;
  double dut1_s_ = 0.0;
};

}  // namespace zenith::astro
