#include "edgevio/common/options.h"

#include <cstdio>
#include <cstdlib>

#include "edgevio/common/format.h"
#include "edgevio/common/table_reader.h"

namespace edgevio::options {

Range Range::orOff() const {
  Range r = *this;
  r.zero_is_off = true;
  return r;
}

Range Range::odd() const {
  Range r = *this;
  r.odd_only = true;
  return r;
}

Range Range::multipleOf(int k) const {
  Range r = *this;
  r.multiple_of = k;
  return r;
}

bool Range::contains(double v) const {
  if (zero_is_off && v == 0.0) return true;
  if (!std::isfinite(v)) return false;
  if (lo_open ? !(v > lo) : !(v >= lo)) return false;
  if (hi_open ? !(v < hi) : !(v <= hi)) return false;
  if (odd_only && std::fmod(std::abs(v), 2.0) != 1.0) return false;
  if (multiple_of > 0 && std::fmod(v, multiple_of) != 0.0) return false;
  return true;
}

namespace {
std::string num(double v) { return formatText("%g", v); }
}  // namespace

std::string Range::text() const {
  const bool has_lo = std::isfinite(lo), has_hi = std::isfinite(hi);
  std::string interval;
  if (has_lo && has_hi)
    interval = std::string(lo_open ? "(" : "[") + num(lo) + ", " + num(hi) + (hi_open ? ")" : "]");
  else if (has_lo)
    interval = std::string(lo_open ? "> " : ">= ") + num(lo);
  else if (has_hi)
    interval = std::string(hi_open ? "< " : "<= ") + num(hi);
  std::string s;
  if (odd_only) s = "odd";
  if (multiple_of > 0) s = "a multiple of " + std::to_string(multiple_of);
  if (!interval.empty()) s += s.empty() ? interval : (interval[0] == '[' || interval[0] == '(' ? ", in " : ", ") + interval;
  if (zero_is_off) s = "0 (off) or " + s;
  return s;
}

Range closed(double lo, double hi) { return Range{lo, hi, false, false}; }
Range halfOpen(double lo, double hi) { return Range{lo, hi, false, true}; }
Range atLeast(double lo) { return Range{lo, std::numeric_limits<double>::infinity(), false, false}; }
Range above(double lo) { return Range{lo, std::numeric_limits<double>::infinity(), true, false}; }

std::string formatNumber(double v) {
  char buf[40];
  for (int precision = 6; precision <= 17; ++precision) {
    std::snprintf(buf, sizeof buf, "%.*g", precision, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  std::string s = buf;
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";  // keep it a float for readers
  return s;
}

bool parseNumber(const std::string& s, double* out) { return parseFiniteDouble(s, out); }

bool parseInteger(const std::string& s, int* out) {
  double v = 0.0;
  if (!parseFiniteDouble(s, &v) || v != std::floor(v) || std::abs(v) > 2e9) return false;
  *out = static_cast<int>(v);
  return true;
}

std::string quote(const std::string& s) {
  std::string q = "\"";
  for (char c : s) q += c == '"' || c == '\\' ? std::string("\\") + c : std::string(1, c);
  return q + "\"";
}

namespace detail {

std::string format(const std::vector<double>& v) {
  std::string s = "[";
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + formatNumber(v[i]);
  return s + "]";
}

std::string parse(const Value& v, double* out) {
  return !v.is_list && parseNumber(v.scalar, out) ? "" : "a number";
}

std::string parse(const Value& v, int* out) {
  return !v.is_list && parseInteger(v.scalar, out) ? "" : "an integer";
}

std::string parse(const Value& v, bool* out) {
  if (!v.is_list && (v.scalar == "true" || v.scalar == "false")) {
    *out = v.scalar == "true";
    return "";
  }
  return "true or false";
}

std::string parse(const Value& v, std::string* out) {
  if (v.is_list) return "a string";
  *out = v.scalar;
  return "";
}

std::string parse(const Value& v, std::vector<double>* out) {
  if (!v.is_list) return "a list of numbers";
  std::vector<double> r;
  for (const std::string& item : v.items) {
    double d = 0.0;
    if (!parseNumber(item, &d)) return "a list of numbers";
    r.push_back(d);
  }
  *out = r;
  return "";
}

std::string outOfRange(const Range& r, double v) {
  const std::string valid = r.text();
  return std::string("must be ") + (valid[0] == '[' || valid[0] == '(' ? "in " : "") + valid + " (got " + num(v) + ")";
}

}  // namespace detail

}  // namespace edgevio::options
