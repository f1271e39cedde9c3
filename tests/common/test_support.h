#pragma once
// Helpers shared by the tests: numeric Jacobians, temporary folders, the shared data folder.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "edgevio/common/error.h"

namespace edgevio::test {

/// Folder of ../shared/data (env EDGEVIO_DATA_DIR overrides); "" when absent.
std::string sharedDataDir();
/// Skips the current test, naming what is missing, when the shared data is absent.
#define EDGEVIO_REQUIRE_SHARED_DATA(subpath)                                                   \
  const std::string data_path = ::edgevio::test::sharedDataPath(subpath);                      \
  if (data_path.empty()) GTEST_SKIP() << "shared data not found: " << (subpath)                \
                                      << " (set EDGEVIO_DATA_DIR to the shared/data folder)"
std::string sharedDataPath(const std::string& subpath);
/// The source tree (for config/euroc.yaml).
std::string sourceDir();

/// A fresh empty folder under the system temp dir, removed on destruction.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::string& path() const { return path_; }
  std::string file(const std::string& name) const { return path_ + "/" + name; }
  /// Writes text to path()/name (creating folders) and returns the full path.
  std::string write(const std::string& name, const std::string& text) const;

 private:
  std::string path_;
};

/// The folder `render(out_dir)` writes, made once per build of the test
/// program and shared by its processes (ctest runs every test in a process
/// of its own, and a render takes several times the test's own work). The
/// simulator is deterministic, so another process's copy is this one's. It
/// lives in the build tree (render_cache/), under a stamp of the program's
/// file: a rebuild renders again. `key` names the render; a test must not
/// change the folder.
std::string sharedRender(const std::string& key, const std::function<void(const std::string& out_dir)>& render);

/// The whole file as bytes ("" if it cannot be read).
std::string readFile(const std::string& path);

/// Runs f, expecting an InputError whose message contains every fragment.
template <class F>
void expectInputError(F&& f, const std::vector<std::string>& fragments) {
  try {
    f();
    ADD_FAILURE() << "expected an InputError";
  } catch (const InputError& e) {
    for (const auto& frag : fragments)
      EXPECT_NE(std::string(e.what()).find(frag), std::string::npos) << "'" << frag << "' not in: " << e.what();
  }
}

/// Expects every fragment to occur in text.
void expectContainsAll(const std::string& text, const std::vector<std::string>& fragments);

/// Central-difference Jacobian of f: R^n → R^m at x, step h.
Eigen::MatrixXd numericJacobian(const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& f,
                                const Eigen::VectorXd& x, double h = 1e-6);

/// Expects |analytic − numeric| ≤ tol elementwise, printing both on failure.
void expectJacobianNear(const Eigen::MatrixXd& analytic, const Eigen::MatrixXd& numeric, double tol,
                        const std::string& what);

}  // namespace edgevio::test
