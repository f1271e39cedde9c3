#pragma once
// One table per options struct: every option's key, default, unit, meaning
// and valid values, written once. The struct's constructor takes its defaults
// from the table; config/config.h reads and writes YAML, validates and writes
// the reference docs/configuration.md from the same tables.
//
//   struct ExampleOptions {                       // example_options.h
//     int iterations;
//     Weight weight;
//     EDGEVIO_OPTIONS(ExampleOptions)
//   };
//   EDGEVIO_OPTIONS_TABLE(ExampleOptions,         // example_options.cpp
//       number("iterations", &S::iterations, 20, "-", "Gauss-Newton iterations", closed(1, 100)),
//       choice("weight", &S::weight, Weight::kCauchy, kWeightChoices, "robust weight of a residual"))
//
// Inside the table S names the struct and options:: is in scope; an entry is
// a number(), a choice(), the nested() fields of a member struct, or a
// Rule<S>{holds, message} between options.
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace edgevio::options {

/// A value as a config file gives it: one scalar, or a list of scalars.
struct Value {
  bool is_list = false;
  std::string scalar;
  std::vector<std::string> items;
};

/// The valid numbers of an option: an interval whose ends may be open or
/// infinite, optionally also 0 ("off"), odd integers only, or multiples of k.
struct Range {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false, hi_open = false;
  bool zero_is_off = false;
  bool odd_only = false;
  int multiple_of = 0;

  Range orOff() const;          ///< 0 is valid too and means "off"
  Range odd() const;
  Range multipleOf(int k) const;
  bool contains(double v) const;
  /// "[1, 100]", "> 0", "0 (off) or > 1", "odd, in [5, 51]", "" (any number).
  std::string text() const;
};
Range closed(double lo, double hi);  ///< [lo, hi]
Range halfOpen(double lo, double hi);  ///< [lo, hi)
Range atLeast(double lo);            ///< [lo, ∞)
Range above(double lo);              ///< (lo, ∞)

/// One choice of an enum option: its value, its name in files, what it means.
template <class E>
struct Choice {
  E value;
  const char* name;
  const char* meaning;
};

/// The name of `value` among `choices` ("?" if absent).
template <class E, std::size_t N>
const char* nameOf(const Choice<E> (&choices)[N], E value) {
  for (const Choice<E>& c : choices)
    if (c.value == value) return c.name;
  return "?";
}

/// Parses a name among `choices`; false when it is none of them.
template <class E, std::size_t N>
bool parseChoice(const Choice<E> (&choices)[N], const std::string& name, E* out) {
  for (const Choice<E>& c : choices)
    if (name == c.name) {
      *out = c.value;
      return true;
    }
  return false;
}

/// "a | b | c": the names of `choices`, for messages.
template <class E, std::size_t N>
std::string choiceList(const Choice<E> (&choices)[N]) {
  std::string s;
  for (const Choice<E>& c : choices) s += (s.empty() ? "" : " | ") + std::string(c.name);
  return s;
}

/// One option of struct S, type-erased: what the table holds.
template <class S>
struct Field {
  const char* key;
  const char* unit;      ///< "-" for none
  std::string meaning;   ///< one line; for a choice, each choice's meaning appended
  std::string valid;     ///< the valid values as text ("" when any value of the type is)
  std::string default_text;
  std::function<void(S&)> set_default;
  std::function<std::string(const S&)> format;  ///< the value as YAML
  /// Parses v into s; "" on success, else what was expected ("a number").
  std::function<std::string(S&, const Value&)> parse;
  /// "" when the value in s is valid, else why not (for "key: <why>").
  std::function<std::string(const S&)> check;
};

/// A rule between options of one struct: `holds(s)` or the message.
template <class S>
struct Rule {
  std::function<bool(const S&)> holds;
  const char* message;
};

template <class S>
struct Table {
  std::vector<Field<S>> fields;
  std::vector<Rule<S>> rules = {};
};

// Scalar formatting and parsing, shared by every field type.
std::string formatNumber(double v);  ///< shortest text that reads back to v, with a '.' or exponent
bool parseNumber(const std::string& s, double* out);  ///< a whole finite number
bool parseInteger(const std::string& s, int* out);
std::string quote(const std::string& s);

namespace detail {
template <class T>
struct Identity {
  using type = T;
};
inline std::string format(double v) { return formatNumber(v); }
inline std::string format(int v) { return std::to_string(v); }
inline std::string format(bool v) { return v ? "true" : "false"; }
inline std::string format(const std::string& v) { return quote(v); }
std::string format(const std::vector<double>& v);
std::string parse(const Value& v, double* out);
std::string parse(const Value& v, int* out);
std::string parse(const Value& v, bool* out);
std::string parse(const Value& v, std::string* out);
std::string parse(const Value& v, std::vector<double>* out);
std::string outOfRange(const Range& r, double v);
inline bool inRange(const Range& r, double v) { return r.contains(v); }
inline bool inRange(const Range& r, const std::vector<double>& v) {
  for (double x : v)
    if (!r.contains(x)) return false;
  return true;
}
}  // namespace detail

/// A number, flag, text or list of numbers; `range` applies to numbers (and
/// to every element of a list).
template <class S, class T>
Field<S> number(const char* key, T S::*member, typename detail::Identity<T>::type default_value, const char* unit,
                const char* meaning, Range range = {}) {
  Field<S> f;
  f.key = key;
  f.unit = unit;
  f.meaning = meaning;
  f.default_text = detail::format(default_value);
  f.set_default = [member, default_value](S& s) { s.*member = default_value; };
  f.format = [member](const S& s) { return detail::format(s.*member); };
  f.parse = [member](S& s, const Value& v) { return detail::parse(v, &(s.*member)); };
  if constexpr (std::is_same_v<T, double> || std::is_same_v<T, int> || std::is_same_v<T, std::vector<double>>) {
    f.valid = range.text();
    f.check = [member, range](const S& s) {
      if (detail::inRange(range, s.*member)) return std::string();
      if constexpr (std::is_same_v<T, std::vector<double>>) return "every value must be " + range.text();  // NOLINT
      else return detail::outOfRange(range, static_cast<double>(s.*member));
    };
  } else {
    f.check = [](const S&) { return std::string(); };
  }
  return f;
}

/// One of the named values of an enum.
template <class S, class E, std::size_t N>
Field<S> choice(const char* key, E S::*member, E default_value, const Choice<E> (&choices)[N], const char* meaning) {
  Field<S> f;
  f.key = key;
  f.unit = "-";
  f.meaning = meaning;
  for (std::size_t i = 0; i < N; ++i)
    f.meaning += std::string(i == 0 ? ": " : " | ") + choices[i].name + " (" + choices[i].meaning + ")";
  f.valid = choiceList(choices);
  f.default_text = nameOf(choices, default_value);
  f.set_default = [member, default_value](S& s) { s.*member = default_value; };
  f.format = [member, &choices](const S& s) { return std::string(nameOf(choices, s.*member)); };
  f.parse = [member, &choices](S& s, const Value& v) {
    if (!v.is_list && parseChoice(choices, v.scalar, &(s.*member))) return std::string();
    return "one of " + choiceList(choices);
  };
  f.check = [](const S&) { return std::string(); };
  return f;
}

/// The fields of a nested struct (S::member), under their own keys.
template <class S, class Inner>
std::vector<Field<S>> nested(Inner S::*member, const Table<Inner>& inner) {
  std::vector<Field<S>> out;
  for (const Field<Inner>& g : inner.fields) {
    Field<S> f;
    f.key = g.key;
    f.unit = g.unit;
    f.meaning = g.meaning;
    f.valid = g.valid;
    f.default_text = g.default_text;
    f.set_default = [member, g](S& s) { g.set_default(s.*member); };
    f.format = [member, g](const S& s) { return g.format(s.*member); };
    f.parse = [member, g](S& s, const Value& v) { return g.parse(s.*member, v); };
    f.check = [member, g](const S& s) { return g.check(s.*member); };
    out.push_back(std::move(f));
  }
  return out;
}

template <class S>
void setDefaults(S& s) {
  for (const Field<S>& f : S::table().fields) f.set_default(s);
}

/// "" when every option of s is valid, else the first problem as "key: why".
template <class S>
std::string validate(const S& s) {
  const Table<S>& t = S::table();
  for (const Field<S>& f : t.fields)
    if (std::string why = f.check(s); !why.empty()) return std::string(f.key) + ": " + why;
  for (const Rule<S>& r : t.rules)
    if (!r.holds(s)) return r.message;
  return {};
}

namespace detail {
template <class S>
void append(Table<S>& t, Field<S> f) {
  t.fields.push_back(std::move(f));
}
template <class S>
void append(Table<S>& t, std::vector<Field<S>> fs) {
  for (Field<S>& f : fs) t.fields.push_back(std::move(f));
}
template <class S>
void append(Table<S>& t, Rule<S> r) {
  t.rules.push_back(std::move(r));
}
}  // namespace detail

/// The table of S from its entries in order: fields, nested() lists, rules.
template <class S, class... Entries>
Table<S> tableOf(Entries&&... entries) {
  Table<S> t;
  (detail::append<S>(t, std::forward<Entries>(entries)), ...);
  return t;
}

}  // namespace edgevio::options

/// In an options struct: the constructor that sets the table's defaults, and
/// the table's declaration.
#define EDGEVIO_OPTIONS(Struct)                                   \
  Struct() { ::edgevio::options::setDefaults(*this); }            \
  static const ::edgevio::options::Table<Struct>& table();

/// In the module's .cpp (compiled once: a table instantiates a std::function
/// per field and check, 25 s of compile time in every file that built a
/// Config under the sanitizers): the table, from number(), choice() and
/// nested() entries.
#define EDGEVIO_OPTIONS_TABLE(Struct, ...)                                      \
  const ::edgevio::options::Table<Struct>& Struct::table() {                    \
    using S = Struct;                                                           \
    using namespace ::edgevio::options;                                         \
    static const Table<S> t = tableOf<S>(__VA_ARGS__);                          \
    return t;                                                                   \
  }
