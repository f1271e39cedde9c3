#include "edgevio/sim/simulation_record.h"

#include <cstdlib>
#include <filesystem>
#include <type_traits>

#include "edgevio/common/error.h"
#include "edgevio/common/options.h"
#include "edgevio/common/yaml_file.h"
#include "edgevio/config/config.h"
#include "edgevio/sim/faults.h"

namespace edgevio::sim {

namespace {

/// A scalar of a simulation record; throws naming the file and line where it is missing or not one.
template <class T>
T recordValue(const YAML::Node& root, const char* key, const std::string& path) {
  const YAML::Node n = root[key];
  if (!n || !n.IsScalar())
    throw InputError(path, n ? yamlLine(n) : 0, std::string("'") + key + "' is missing or not a value (a render's "
                                                    "simulation.yaml is written by edgevio simulate; render it again)");
  const std::string& text = n.Scalar();
  T v{};
  std::string expected;
  if constexpr (std::is_same_v<T, std::string> || std::is_same_v<T, bool> || std::is_same_v<T, int>) {
    expected = options::detail::parse(options::Value{false, text, {}}, &v);
  } else {
    // Own number parsing: the options' parser takes finite numbers only, and a record's duration may be "nan"
    // (a run to the trajectory's end); seeds use all 64 bits.
    char* end = nullptr;
    if constexpr (std::is_integral_v<T>)
      v = static_cast<T>(std::strtoull(text.c_str(), &end, 10));
    else
      v = static_cast<T>(std::strtod(text.c_str(), &end));
    if (end == text.c_str() || *end != '\0') expected = "a number";
  }
  if (!expected.empty()) throw InputError(path, yamlLine(n), std::string("'") + key + "': expected " + expected);
  return v;
}

}  // namespace

SimulationRecord loadSimulationRecord(const std::string& folder) {
  const std::string path = (std::filesystem::path(folder) / "simulation.yaml").string();
  const YAML::Node root = loadYamlFile(path);
  if (!root || !root.IsMap()) throw InputError(path, 0, "not a simulation record (edgevio simulate writes one beside mav0)");
  SimulationRecord r;
  SimRequest& q = r.request;
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
      try {
        q.faults.push_back(parseFault(item.Scalar()));
      } catch (const InputError& e) {
        throw InputError(path, yamlLine(item), std::string("'faults': ") + e.what());
      }
    }
  }
  const YAML::Node section = root["sim"];
  if (!section || !section.IsMap()) throw InputError(path, section ? yamlLine(section) : 0, "'sim' must be a mapping of sim options");
  readSimOptions(section, path, &r.options);
  if (const std::string e = options::validate(r.options); !e.empty()) throw InputError(path, 0, "invalid value: sim." + e);
  return r;
}

}  // namespace edgevio::sim
