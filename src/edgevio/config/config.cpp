#include "edgevio/config/config.h"
#include "edgevio/config/simulation_record.h"

#include <cstdlib>
#include <filesystem>
#include <ostream>
#include <set>
#include <type_traits>

#include "edgevio/common/error.h"
#include "edgevio/common/yaml_file.h"
#include "edgevio/sim/faults.h"

namespace edgevio {

namespace {

template <class Options>
using Fields = std::vector<options::Field<Options>>;

template <class Options>
const Fields<Options>& fieldsOf(const Options&) {
  return Options::table().fields;
}

/// Throws for the first key of `map` not in `known`, listing the valid ones.
void rejectUnknown(const YAML::Node& map, const std::set<std::string>& known, const std::string& path,
                   const std::string& what, const std::string& prefix) {
  for (const auto& kv : map) {
    if (!kv.first.IsScalar())
      throw InputError(path, yamlLine(kv.first), "a " + what + " must be a plain name, not a list or a map ('? ...' in YAML)");
    const std::string key = kv.first.Scalar();
    if (known.count(key)) continue;
    std::string valid;
    for (const auto& k : known) valid += (valid.empty() ? "" : ", ") + k;
    throw InputError(path, yamlLine(kv.first), "unknown " + what + " '" + prefix + key + "' (valid " + what + "s: " + valid + ")");
  }
}

/// A YAML value as options::Value; false when it is neither a scalar nor a list of scalars.
bool toValue(const YAML::Node& n, options::Value* v) {
  if (n.IsScalar()) {
    v->scalar = n.Scalar();
    return true;
  }
  if (!n.IsSequence()) return false;
  v->is_list = true;
  for (const auto& item : n) {
    if (!item.IsScalar()) return false;
    v->items.push_back(item.Scalar());
  }
  return true;
}

template <class Options>
void readSection(const YAML::Node& node, const std::string& section, const std::string& path, Options* options,
                 std::vector<std::string>* missing) {
  std::set<std::string> known;
  for (const options::Field<Options>& f : fieldsOf(*options)) {
    known.insert(f.key);
    const YAML::Node n = node.IsMap() ? node[f.key] : YAML::Node();
    if (!n) {
      if (missing) missing->push_back(section + "." + f.key);
      continue;
    }
    options::Value v;
    std::string expected = toValue(n, &v) ? f.parse(*options, v) : "a value";
    if (!expected.empty()) throw InputError(path, yamlLine(n), "'" + section + "." + f.key + "': expected " + expected);
    // Its own bounds here, where the line is known; rules across keys are Config::validate's.
    if (const std::string why = f.check(*options); !why.empty())
      throw InputError(path, yamlLine(n), "invalid value: " + section + "." + f.key + ": " + why);
  }
  if (node.IsMap()) rejectUnknown(node, known, path, "key", section + ".");
}

/// A Markdown table cell: '|' escaped.
std::string escapeCell(const std::string& s) {
  std::string e;
  for (char c : s) e += c == '|' ? std::string("\\|") : std::string(1, c);
  return e;
}

/// A scalar of a simulation record; throws naming the file and line where it is missing or not one.
template <class T>
T recordValue(const YAML::Node& root, const char* key, const std::string& path) {
  const YAML::Node n = root[key];
  if (!n || !n.IsScalar())
    throw InputError(path, n ? yamlLine(n) : 0, std::string("'") + key + "' is missing or not a value (a render's "
                                                    "simulation.yaml is written by edgevio simulate; render it again)");
  const std::string& text = n.Scalar();
  T v{};
  if constexpr (std::is_same_v<T, std::string>) {
    v = text;
  } else if constexpr (std::is_same_v<T, bool>) {
    if (text != "true" && text != "false") throw InputError(path, yamlLine(n), std::string("'") + key + "': expected true or false");
    v = text == "true";
  } else {
    char* end = nullptr;
    if constexpr (std::is_integral_v<T>)
      v = static_cast<T>(std::strtoull(text.c_str(), &end, 10));  // seeds use all 64 bits
    else
      v = static_cast<T>(std::strtod(text.c_str(), &end));  // reads "nan" too: the duration of a run to the file's end
    if (end == text.c_str() || *end != '\0') throw InputError(path, yamlLine(n), std::string("'") + key + "': expected a number");
  }
  return v;
}

}  // namespace

SimulationRecord loadSimulationRecord(const std::string& folder) {
  const std::string path = (std::filesystem::path(folder) / "simulation.yaml").string();
  const YAML::Node root = loadYamlFile(path);
  if (!root || !root.IsMap()) throw InputError(path, 0, "not a simulation record (edgevio simulate writes one beside mav0)");
  SimulationRecord r;
  sim::SimRequest& q = r.request;
  q.out_dir = folder;
  q.trajectory_file = recordValue<std::string>(root, "trajectory", path);
  q.scenario = recordValue<std::string>(root, "scenario", path);
  q.start_s = recordValue<double>(root, "start_s", path);
  q.duration_s = recordValue<double>(root, "duration_s", path);
  q.seed = recordValue<std::uint64_t>(root, "seed", path);
  q.imu = recordValue<std::string>(root, "imu", path);
  q.noise = recordValue<bool>(root, "noise", path);
  q.blur_ms = recordValue<double>(root, "blur_ms", path);
  q.exposure_changes = recordValue<bool>(root, "exposure_changes", path);
  q.drop_rate = recordValue<double>(root, "drop_rate", path);
  q.skip = recordValue<int>(root, "skip", path);
  q.calib = recordValue<std::string>(root, "calib", path);
  if (const YAML::Node f = root["faults"]; f && f.IsSequence()) {
    for (const auto& item : f) {
      if (!item.IsScalar()) throw InputError(path, yamlLine(item), "'faults': expected a list of fault specs");
      q.faults.push_back(sim::parseFault(item.Scalar()));
    }
  }
  const YAML::Node section = root["sim"];
  if (!section || !section.IsMap()) throw InputError(path, section ? yamlLine(section) : 0, "'sim' must be a mapping of sim options");
  readSection(section, "sim", path, &r.options, nullptr);
  if (const std::string e = options::validate(r.options); !e.empty()) throw InputError(path, 0, "invalid value: sim." + e);
  return r;
}

std::string Config::validate() const {
  std::string error;
  forEachSection(*this, [&](const char* name, const char*, const auto& section) {
    if (!error.empty()) return;
    if (const std::string e = options::validate(section); !e.empty()) error = std::string(name) + "." + e;
  });
  return error;
}

Config loadConfig(const std::string& path, std::vector<std::string>* missing_keys) {
  const YAML::Node root = loadYamlFile(path);
  if (root && !root.IsNull() && !root.IsMap()) throw InputError(path, yamlLine(root), "a config file is a mapping of sections");
  Config config;
  std::set<std::string> known;
  forEachSection(config, [&](const char* name, const char*, auto& section) {
    known.insert(name);
    const YAML::Node n = root && root.IsMap() ? root[name] : YAML::Node();
    if (n && !n.IsMap()) throw InputError(path, yamlLine(n), "section '" + std::string(name) + "' must be a mapping");
    readSection(n ? n : YAML::Node(YAML::NodeType::Map), name, path, &section, missing_keys);
  });
  if (root && root.IsMap()) rejectUnknown(root, known, path, "section", "");
  const std::string error = config.validate();
  if (!error.empty()) throw InputError(path, 0, "invalid value: " + error);
  return config;
}

void writeConfig(std::ostream& out, const Config& config) {
  out << "# edgevio configuration. Every parameter of every module with its unit and meaning.\n"
         "# Keys left out keep their defaults; unknown keys are errors.\n";
  forEachSection(config, [&](const char* name, const char* meaning, const auto& section) {
    out << "\n# " << meaning << "\n" << name << ":\n";
    for (const auto& f : fieldsOf(section)) {
      std::string line = std::string("  ") + f.key + ": " + f.format(section);
      if (line.size() < 44) line.resize(44, ' ');
      out << line << " # [" << f.unit << "] " << f.meaning << (f.valid.empty() ? "" : "; valid: " + f.valid) << "\n";
    }
  });
}

void writeConfigReference(std::ostream& out) {
  out << "# Configuration reference\n\n"
         "Generated by `edgevio --print-config-reference` from the option tables in the code; do not edit by hand.\n"
         "A config file (`--config FILE`) is YAML with one mapping per section; keys left out keep the defaults below,\n"
         "unknown keys are errors. `edgevio --print-config` writes the whole default file (`config/euroc.yaml`).\n";
  const Config defaults;
  forEachSection(defaults, [&](const char* name, const char* meaning, const auto& section) {
    out << "\n## `" << name << "`\n\n" << meaning << ".\n\n| key | default | unit | valid | meaning |\n|---|---|---|---|---|\n";
    for (const auto& f : fieldsOf(section)) {
      out << "| `" << f.key << "` | `" << f.default_text << "` | " << f.unit << " | " << escapeCell(f.valid) << " | "
          << escapeCell(f.meaning) << " |\n";
    }
  });
}

}  // namespace edgevio
