#include "edgevio/config/config.h"

#include <cmath>
#include <cstdio>
#include <ostream>
#include <set>
#include <sstream>

#include "edgevio/common/error.h"
#include "edgevio/common/table_reader.h"
#include "edgevio/common/yaml_file.h"

namespace edgevio {

namespace {

/// Throws for the first key of `map` not in `known`, listing the valid ones.
void rejectUnknown(const YAML::Node& map, const std::set<std::string>& known, const std::string& path,
                   const std::string& what, const std::string& prefix) {
  for (const auto& kv : map) {
    const std::string key = kv.first.as<std::string>();
    if (known.count(key)) continue;
    std::string valid;
    for (const auto& k : known) valid += (valid.empty() ? "" : ", ") + k;
    throw InputError(path, yamlLine(kv.first), "unknown " + what + " '" + prefix + key + "' (valid " + what + "s: " + valid + ")");
  }
}

std::string shortestDouble(double v) {
  char buf[40];
  for (int precision = 6; precision <= 17; ++precision) {
    std::snprintf(buf, sizeof buf, "%.*g", precision, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  std::string s = buf;
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";  // keep it a float for readers
  return s;
}

std::string typeName(double) { return "a number"; }
std::string typeName(int) { return "an integer"; }
[[maybe_unused]] std::string typeName(bool) { return "true or false"; }
std::string typeName(const std::string&) { return "a string"; }
std::string typeName(const std::vector<double>&) { return "a list of numbers"; }

bool parseValue(const YAML::Node& n, double* out) { return n.IsScalar() && parseFiniteDouble(n.Scalar(), out); }
bool parseValue(const YAML::Node& n, int* out) {
  double v = 0.0;
  if (!parseValue(n, &v) || v != std::floor(v) || std::abs(v) > 2e9) return false;
  *out = static_cast<int>(v);
  return true;
}
[[maybe_unused]] bool parseValue(const YAML::Node& n, bool* out) {
  if (!n.IsScalar()) return false;
  const std::string& s = n.Scalar();
  if (s == "true") *out = true;
  else if (s == "false") *out = false;
  else return false;
  return true;
}
bool parseValue(const YAML::Node& n, std::string* out) {
  if (!n.IsScalar()) return false;
  *out = n.Scalar();
  return true;
}
bool parseValue(const YAML::Node& n, std::vector<double>* out) {
  if (!n.IsSequence()) return false;
  std::vector<double> v;
  for (const auto& item : n) {
    double d = 0.0;
    if (!parseValue(item, &d)) return false;
    v.push_back(d);
  }
  *out = v;
  return true;
}

std::string formatValue(double v) { return shortestDouble(v); }
std::string formatValue(int v) { return std::to_string(v); }
[[maybe_unused]] std::string formatValue(bool v) { return v ? "true" : "false"; }
std::string formatValue(const std::string& v) { return "\"" + v + "\""; }
std::string formatValue(const std::vector<double>& v) {
  std::string s = "[";
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + shortestDouble(v[i]);
  return s + "]";
}

/// Reads one section's keys into its options struct.
class SectionReader {
 public:
  SectionReader(const YAML::Node& node, std::string section, std::string path, std::vector<std::string>* missing)
      : node_(node), section_(std::move(section)), path_(std::move(path)), missing_(missing) {}

  template <class T>
  void operator()(const char* key, T& value, const char* /*unit*/, const char* /*doc*/) {
    known_.insert(key);
    const YAML::Node n = node_[key];
    if (!n) {
      if (missing_) missing_->push_back(section_ + "." + key);
      return;
    }
    if (!parseValue(n, &value))
      throw InputError(path_, yamlLine(n), "'" + section_ + "." + key + "': expected " + typeName(value));
  }

  void rejectUnknownKeys() const { rejectUnknown(node_, known_, path_, "key", section_ + "."); }

 private:
  YAML::Node node_;
  std::string section_, path_;
  std::vector<std::string>* missing_;
  std::set<std::string> known_;
};

class ConfigReader {
 public:
  ConfigReader(const YAML::Node& root, std::string path, std::vector<std::string>* missing)
      : root_(root), path_(std::move(path)), missing_(missing) {}

  template <class Options>
  void operator()(const char* section, Options& options, const char* /*doc*/) {
    known_.insert(section);
    const YAML::Node n = root_[section];
    if (!n) {
      SectionReader collect(YAML::Node(YAML::NodeType::Map), section, path_, missing_);
      options.visit(collect);
      return;
    }
    if (!n.IsMap()) throw InputError(path_, yamlLine(n), "section '" + std::string(section) + "' must be a mapping");
    SectionReader reader(n, section, path_, missing_);
    options.visit(reader);
    reader.rejectUnknownKeys();
  }

  void rejectUnknownSections() const { rejectUnknown(root_, known_, path_, "section", ""); }

 private:
  YAML::Node root_;
  std::string path_;
  std::vector<std::string>* missing_;
  std::set<std::string> known_;
};

class SectionWriter {
 public:
  explicit SectionWriter(std::ostream& out) : out_(out) {}
  template <class T>
  void operator()(const char* key, T& value, const char* unit, const char* doc) {
    std::string line = std::string("  ") + key + ": " + formatValue(value);
    if (line.size() < 44) line.resize(44, ' ');
    out_ << line << " # [" << unit << "] " << doc << "\n";
  }

 private:
  std::ostream& out_;
};

class ConfigWriter {
 public:
  explicit ConfigWriter(std::ostream& out) : out_(out) {}
  template <class Options>
  void operator()(const char* section, Options& options, const char* doc) {
    out_ << "\n# " << doc << "\n" << section << ":\n";
    SectionWriter w(out_);
    options.visit(w);
  }

 private:
  std::ostream& out_;
};

class ConfigValidator {
 public:
  template <class Options>
  void operator()(const char* section, const Options& options, const char* /*doc*/) {
    if (!error.empty()) return;
    const std::string e = options.validate();
    if (!e.empty()) error = std::string(section) + "." + e;
  }
  std::string error;
};

}  // namespace

std::string Config::validate() const {
  ConfigValidator v;
  const_cast<Config*>(this)->visitSections(v);  // visit() does not modify; it is non-const to serve readers too
  return v.error;
}

Config loadConfig(const std::string& path, std::vector<std::string>* missing_keys) {
  const YAML::Node root = loadYamlFile(path);
  Config config;
  ConfigReader reader(root, path, missing_keys);
  config.visitSections(reader);
  reader.rejectUnknownSections();
  const std::string error = config.validate();
  if (!error.empty()) throw InputError(path, 0, "invalid value: " + error);
  return config;
}

void writeConfig(std::ostream& out, const Config& config) {
  out << "# edgevio configuration. Every parameter of every module with its unit and meaning.\n"
         "# Keys left out keep their defaults; unknown keys are errors.\n";
  Config copy = config;
  ConfigWriter w(out);
  copy.visitSections(w);
}

}  // namespace edgevio
