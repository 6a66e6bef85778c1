#include "astro/civil_time.h"

#include <erfa.h>
#include <erfam.h>
#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace zenith::astro {
namespace {

[[noreturn]] void bad(const std::string& text, const std::string& why) {
  throw std::invalid_argument("time '" + text + "': " + why +
                              " (expected ISO 8601 UTC, e.g. \"2026-12-21T16:30:00Z\")");
}

int digits(const std::string& text, std::size_t& at, int count) {
  int value = 0;
  for (int i = 0; i < count; ++i, ++at) {
    if (at >= text.size() || text[at] < '0' || text[at] > '9')
      bad(text, "a digit expected at character " + std::to_string(at + 1));
    value = value * 10 + (text[at] - '0');
  }
  return value;
}

void expect(const std::string& text, std::size_t& at, char c) {
  if (at >= text.size() || text[at] != c)
    bad(text, std::string("'") + c + "' expected at character " + std::to_string(at + 1));
  ++at;
}

}  // namespace

UtcTime parse_utc_time(const std::string& text) {
  UtcTime t;
  std::size_t at = 0;
  t.year = digits(text, at, 4);
  expect(text, at, '-');
  t.month = digits(text, at, 2);
  expect(text, at, '-');
  t.day = digits(text, at, 2);
  if (at >= text.size() || (text[at] != 'T' && text[at] != ' ')) bad(text, "'T' expected after the date");
  ++at;
  t.hour = digits(text, at, 2);
  expect(text, at, ':');
  t.minute = digits(text, at, 2);
  t.second = 0.0;
  if (at < text.size() && text[at] == ':') {
    ++at;
    t.second = digits(text, at, 2);
    if (at < text.size() && text[at] == '.') {
      ++at;
      double scale = 0.1;
      if (at >= text.size() || text[at] < '0' || text[at] > '9') bad(text, "digits expected after the decimal point");
      for (; at < text.size() && text[at] >= '0' && text[at] <= '9'; ++at, scale *= 0.1)
        t.second += (text[at] - '0') * scale;
    }
  }
  const std::string zone = text.substr(at);
  if (zone != "Z" && zone != "+00:00" && zone != "+0000")
    bad(text,
        zone.empty() ? "no time zone: end with 'Z' (UTC)" : "time zone '" + zone + "': only UTC ('Z') is accepted");
  if (t.month < 1 || t.month > 12) bad(text, "month must be in [1, 12]");
  if (t.day < 1 || t.day > 31) bad(text, "day must be in [1, 31]");
  if (t.hour > 23) bad(text, "hour must be in [0, 23]");
  if (t.minute > 59) bad(text, "minute must be in [0, 59]");
  if (t.second >= 61.0) bad(text, "second must be below 61 (60 only in a leap second)");
  return t;
}

std::string format_utc_time(const UtcTime& t) {
  return fmt::format("{:04}-{:02}-{:02}T{:02}:{:02}:{:06.3f}Z", t.year, t.month, t.day, t.hour, t.minute, t.second);
}

AstroTime AstroTime::from_utc(const UtcTime& utc, double dut1_s) {
  JulianDate jd;
  const int status =
      eraDtf2d("UTC", utc.year, utc.month, utc.day, utc.hour, utc.minute, utc.second, &jd.day1, &jd.day2);
  if (status < 0) {
    const char* why = status == -1   ? "year before -4799"
                      : status == -2 ? "bad month"
                      : status == -3 ? "bad day of the month"
                      : status == -4 ? "bad hour"
                      : status == -5 ? "bad minute"
                                     : "bad second (a leap second where there is none)";
    throw std::invalid_argument("time " + format_utc_time(utc) + ": " + why);
  }
  return from_utc_julian(jd, dut1_s);
}

AstroTime AstroTime::from_utc_julian(JulianDate utc, double dut1_s) {
  if (!(std::abs(dut1_s) <= 0.9))
    throw std::invalid_argument("dut1_s " + std::to_string(dut1_s) + ": must be in [-0.9, 0.9] s");
  AstroTime t;
  t.utc_ = utc;
  t.dut1_s_ = dut1_s;
  JulianDate tai;
  if (eraUtctai(utc.day1, utc.day2, &tai.day1, &tai.day2) < 0)
    throw std::invalid_argument(
        fmt::format("Julian date {:.6f} UTC: ERFA cannot convert it to TAI (UTC starts in 1960)", utc.value()));
  eraTaitt(tai.day1, tai.day2, &t.tt_.day1, &t.tt_.day2);
  if (eraUtcut1(utc.day1, utc.day2, dut1_s, &t.ut1_.day1, &t.ut1_.day2) < 0)
    throw std::invalid_argument(fmt::format("Julian date {:.6f} UTC: ERFA cannot convert it to UT1", utc.value()));
  return t;
}

AstroTime AstroTime::from_tt(double tt_julian_date, double dut1_s) {
  JulianDate tai, utc;
  eraTttai(tt_julian_date, 0.0, &tai.day1, &tai.day2);
  if (eraTaiutc(tai.day1, tai.day2, &utc.day1, &utc.day2) < 0)
    throw std::invalid_argument(fmt::format("Julian date {:.6f} TT: ERFA cannot convert it to UTC", tt_julian_date));
  return from_utc_julian(utc, dut1_s);
}

AstroTime AstroTime::plus_seconds(double seconds) const {
  JulianDate moved = utc_;
  moved.day2 += seconds / 86400.0;
  return from_utc_julian(moved, dut1_s_);
}

double AstroTime::julian_years_since_j2000() const { return ((tt_.day1 - ERFA_DJ00) + tt_.day2) / ERFA_DJY; }

UtcTime AstroTime::calendar_utc() const {
  int y = 0, m = 0, d = 0, hmsf[4] = {0, 0, 0, 0};
  eraD2dtf("UTC", 6, utc_.day1, utc_.day2, &y, &m, &d, hmsf);
  return UtcTime{y, m, d, hmsf[0], hmsf[1], hmsf[2] + hmsf[3] * 1e-6};
}

}  // namespace zenith::astro
