#include "edgevio/common/yaml_file.h"

#include <fstream>
#include <sstream>

#include "edgevio/common/error.h"
#include "edgevio/common/table_reader.h"

namespace edgevio {

YAML::Node loadYamlFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, 0, "cannot open YAML file for reading (check the path)");
  std::stringstream buffer;
  buffer << in.rdbuf();
  std::string text = buffer.str();
  if (text.rfind("%YAML:", 0) == 0) text[0] = '#';  // OpenCV header; YAML itself wants "%YAML 1.x"
  try {
    YAML::Node root = YAML::Load(text);
    if (!root.IsMap()) throw InputError(path, 1, "expected a YAML mapping (key: value lines) at the top level");
    return root;
  } catch (const YAML::Exception& e) {
    throw InputError(path, e.mark.is_null() ? 0 : static_cast<std::size_t>(e.mark.line) + 1,
                     "invalid YAML: " + e.msg);
  }
}

std::size_t yamlLine(const YAML::Node& node) {
  const YAML::Mark m = node.Mark();
  return m.is_null() ? 0 : static_cast<std::size_t>(m.line) + 1;
}

YAML::Node yamlRequire(const YAML::Node& parent, const std::string& key, const std::string& path) {
  if (!parent.IsMap()) throw InputError(path, yamlLine(parent), "expected a mapping containing '" + key + "'");
  YAML::Node n = parent[key];
  if (!n) throw InputError(path, yamlLine(parent), "missing key '" + key + "'");
  return n;
}

namespace {
double scalarAsDouble(const YAML::Node& n, const std::string& key, const std::string& path) {
  double v = 0.0;
  if (!n.IsScalar() || !parseFiniteDouble(n.Scalar(), &v))
    throw InputError(path, yamlLine(n), "'" + key + "': expected a finite number");
  return v;
}
}  // namespace

double yamlDouble(const YAML::Node& node, const std::string& key, const std::string& path) {
  return scalarAsDouble(yamlRequire(node, key, path), key, path);
}

std::string yamlString(const YAML::Node& node, const std::string& key, const std::string& path) {
  const YAML::Node n = yamlRequire(node, key, path);
  if (!n.IsScalar()) throw InputError(path, yamlLine(n), "'" + key + "': expected a string");
  return n.Scalar();
}

std::vector<double> yamlDoubles(const YAML::Node& node, const std::string& key, const std::string& path,
                                std::size_t expected_size) {
  const YAML::Node n = yamlRequire(node, key, path);
  if (!n.IsSequence() || n.size() != expected_size)
    throw InputError(path, yamlLine(n),
                     "'" + key + "': expected a list of " + std::to_string(expected_size) + " numbers");
  std::vector<double> v;
  for (const auto& item : n) v.push_back(scalarAsDouble(item, key, path));
  return v;
}

Mat4 yamlMatrix4(const YAML::Node& node, const std::string& key, const std::string& path) {
  const YAML::Node n = yamlRequire(node, key, path);
  Mat4 T;
  if (n.IsMap()) {
    const double rows = yamlDouble(n, "rows", path), cols = yamlDouble(n, "cols", path);
    if (rows != 4.0 || cols != 4.0) throw InputError(path, yamlLine(n), "'" + key + "': expected a 4x4 matrix");
    const std::vector<double> d = yamlDoubles(n, "data", path, 16);
    for (int i = 0; i < 16; ++i) T(i / 4, i % 4) = d[static_cast<std::size_t>(i)];
  } else if (n.IsSequence() && n.size() == 4) {
    for (std::size_t r = 0; r < 4; ++r) {
      const YAML::Node row = n[r];
      if (!row.IsSequence() || row.size() != 4)
        throw InputError(path, yamlLine(n), "'" + key + "': expected 4 rows of 4 numbers");
      for (std::size_t c = 0; c < 4; ++c)
        T(static_cast<int>(r), static_cast<int>(c)) = scalarAsDouble(row[c], key, path);
    }
  } else {
    throw InputError(path, yamlLine(n), "'" + key + "': expected a 4x4 matrix ({rows, cols, data} or 4 rows)");
  }
  const Mat3 R = T.topLeftCorner<3, 3>();
  if ((R.transpose() * R - Mat3::Identity()).norm() > 1e-3 || R.determinant() < 0.0 ||
      (T.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).norm() > 1e-9)
    throw InputError(path, yamlLine(n), "'" + key + "': not a rigid transform (rotation block must be orthonormal)");
  return T;
}

}  // namespace edgevio
