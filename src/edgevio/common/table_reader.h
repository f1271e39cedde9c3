#pragma once
// The one reader of line-based tables: EuRoC CSV files (comma separated,
// '#' header), TUM trajectory files (whitespace separated) and the CSV files
// edgevio writes (a header row of column names, e.g. frames.csv).
// It streams the file line by line, skips blank and '#' lines, strips '\r',
// and converts fields with errors that name the file, line and column.
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

namespace edgevio {

class TableReader {
 public:
  enum class Separator { kComma, kWhitespace };

  enum class Header { kNone, kColumnNames };

  /// Throws InputError when the file cannot be opened. With
  /// Header::kColumnNames the first row names the columns (column()).
  TableReader(std::string path, Separator sep, Header header = Header::kNone);

  /// Reads the next data row; false at end of file.
  bool next();

  std::size_t line() const { return line_; }
  std::size_t size() const { return fields_.size(); }
  const std::string& path() const { return path_; }
  const std::string& field(std::size_t i) const { return fields_.at(i); }

  /// The header's column names (Header::kColumnNames).
  const std::vector<std::string>& columns() const { return names_; }
  /// The index of a named column; throws InputError naming the file when there is none.
  std::size_t column(const std::string& name) const;

  /// Requires at least `n` fields; `what` describes the expected row layout.
  void requireFields(std::size_t n, const std::string& what) const;
  /// Finite double in column i (NaN and inf are errors).
  double number(std::size_t i) const;
  /// A finite number, or "nan" (a value the writer did not know).
  double numberOrNan(std::size_t i) const;
  /// Non-negative integer in column i (nanosecond timestamps).
  std::int64_t integer(std::size_t i) const;
  /// A time in seconds with a fraction, converted exactly enough to nanoseconds
  /// (long double keeps < 1 ns error for Unix-epoch times).
  std::int64_t secondsAsNanoseconds(std::size_t i) const;
  /// Throws InputError at the current line.
  [[noreturn]] void fail(const std::string& what) const;

 private:
  std::string path_;
  Separator sep_;
  std::ifstream in_;
  std::string buffer_;
  std::vector<std::string> fields_;
  std::vector<std::string> names_;
  std::size_t line_ = 0;
};

/// Parses a whole string as a finite double; false if it is not one.
bool parseFiniteDouble(const std::string& s, double* out);

}  // namespace edgevio
