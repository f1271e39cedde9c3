#pragma once
// The one place YAML files are opened: calibration (EuRoC sensor.yaml, Kalibr)
// and the edgevio config. Parse errors and bad values become InputError naming
// the file, the line and the expected value.
#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

#include "edgevio/geometry/types.h"

namespace edgevio {

/// Loads a YAML file. An OpenCV-style `%YAML:1.0` first line (EuRoC) is
/// accepted: it is blanked out, so line numbers still match the file.
YAML::Node loadYamlFile(const std::string& path);

/// 1-based line of a node (0 when unknown).
std::size_t yamlLine(const YAML::Node& node);

/// Typed access to `parent[key]`, throwing InputError(path, line, ...) when the
/// key is missing or the value has the wrong type.
YAML::Node yamlRequire(const YAML::Node& parent, const std::string& key, const std::string& path);
double yamlDouble(const YAML::Node& node, const std::string& key, const std::string& path);
std::string yamlString(const YAML::Node& node, const std::string& key, const std::string& path);
std::vector<double> yamlDoubles(const YAML::Node& node, const std::string& key, const std::string& path,
                                std::size_t expected_size);
/// A 4x4 matrix given as an OpenCV-style {rows, cols, data} map (EuRoC) or as a
/// list of four rows (Kalibr).
Mat4 yamlMatrix4(const YAML::Node& node, const std::string& key, const std::string& path);

}  // namespace edgevio
