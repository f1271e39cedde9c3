#include "edgevio/common/table_reader.h"

#include <limits>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>

#include "edgevio/common/error.h"

namespace edgevio {

namespace {
std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return {};
  const auto e = s.find_last_not_of(" \t\r\n");
  return s.substr(b, e - b + 1);
}

std::string quoted(const std::string& s) {
  constexpr std::size_t kMax = 40;  // hostile input may have megabyte "fields"
  std::string shown = s.size() > kMax ? s.substr(0, kMax) + "..." : s;
  for (char& c : shown)
    if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f) c = '?';
  return "'" + shown + "'";
}
}  // namespace

bool parseFiniteDouble(const std::string& s, double* out) {
  if (s.empty()) return false;
  const char* begin = s.c_str();
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(begin, &end);
  if (end != begin + s.size() || errno == ERANGE || !std::isfinite(v)) return false;
  *out = v;
  return true;
}

TableReader::TableReader(std::string path, Separator sep, Header header) : path_(std::move(path)), sep_(sep), in_(path_) {
  if (!in_) throw InputError(path_, 0, "cannot open file for reading (check the path and permissions)");
  if (header == Header::kColumnNames) {
    if (!next()) throw InputError(path_, 0, "empty file: expected a header row of column names");
    names_ = std::move(fields_);
  }
}

std::size_t TableReader::column(const std::string& name) const {
  for (std::size_t i = 0; i < names_.size(); ++i)
    if (names_[i] == name) return i;
  throw InputError(path_, 1, "no column '" + name + "' in the header");
}

bool TableReader::next() {
  while (std::getline(in_, buffer_)) {
    ++line_;
    const std::string text = trim(buffer_);
    if (text.empty() || text[0] == '#' || text[0] == '%') continue;
    fields_.clear();
    if (sep_ == Separator::kComma) {
      std::size_t start = 0;
      while (true) {
        const std::size_t comma = text.find(',', start);
        fields_.push_back(trim(text.substr(start, comma - start)));
        if (comma == std::string::npos) break;
        start = comma + 1;
      }
    } else {
      std::size_t i = 0;
      while (i < text.size()) {
        while (i < text.size() && (text[i] == ' ' || text[i] == '\t')) ++i;
        std::size_t j = i;
        while (j < text.size() && text[j] != ' ' && text[j] != '\t') ++j;
        if (j > i) fields_.push_back(text.substr(i, j - i));
        i = j;
      }
    }
    return true;
  }
  if (in_.bad()) fail("read error");
  return false;
}

void TableReader::fail(const std::string& what) const { throw InputError(path_, line_, what); }

void TableReader::requireFields(std::size_t n, const std::string& what) const {
  if (fields_.size() < n)
    fail("expected " + std::to_string(n) + " columns (" + what + "), found " + std::to_string(fields_.size()));
}

double TableReader::number(std::size_t i) const {
  double v = 0.0;
  if (i >= fields_.size()) fail("missing column " + std::to_string(i + 1));
  if (!parseFiniteDouble(fields_[i], &v))
    fail("column " + std::to_string(i + 1) + ": expected a finite number, found " + quoted(fields_[i]));
  return v;
}

double TableReader::numberOrNan(std::size_t i) const {
  if (i < fields_.size() && (fields_[i] == "nan" || fields_[i] == "NaN")) return std::numeric_limits<double>::quiet_NaN();
  return number(i);
}

std::int64_t TableReader::integer(std::size_t i) const {
  if (i >= fields_.size()) fail("missing column " + std::to_string(i + 1));
  const std::string& s = fields_[i];
  std::int64_t v = 0;
  bool ok = !s.empty();
  for (char c : s) ok = ok && c >= '0' && c <= '9';
  // from_chars refuses what does not fit in 64 bits (over 292 years in ns).
  ok = ok && std::from_chars(s.data(), s.data() + s.size(), v).ec == std::errc{};
  if (!ok) fail("column " + std::to_string(i + 1) + ": expected a non-negative integer timestamp, found " + quoted(s));
  return v;
}

std::int64_t TableReader::secondsAsNanoseconds(std::size_t i) const {
  if (i >= fields_.size()) fail("missing column " + std::to_string(i + 1));
  const std::string& s = fields_[i];
  char* end = nullptr;
  errno = 0;
  const long double v = std::strtold(s.c_str(), &end);
  if (s.empty() || end != s.c_str() + s.size() || errno == ERANGE || !std::isfinite(v) || v < 0.0L ||
      v > 9.2e9L)
    fail("column " + std::to_string(i + 1) + ": expected a time in seconds (>= 0), found " + quoted(s));
  return static_cast<std::int64_t>(std::llround(v * 1e9L));
}

}  // namespace edgevio
