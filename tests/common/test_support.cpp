#include "common/test_support.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#ifdef EDGEVIO_TSAN
#include <opencv2/core/utility.hpp>
#endif

namespace edgevio::test {

namespace fs = std::filesystem;

#ifdef EDGEVIO_TSAN
namespace {
// ThreadSanitizer cannot see how TBB (not instrumented) hands OpenCV's
// parallel loops to its threads, and reports every such hand-off as a race.
// Under TSan OpenCV runs each function on the calling thread (0: no threads
// of its own), so what TSan checks is edgevio's threads.
[[maybe_unused]] const bool kOpenCvOnTheCallingThread = [] {
  cv::setNumThreads(0);
  return true;
}();
}  // namespace
#endif

std::string sharedDataDir() {
  const char* env = std::getenv("EDGEVIO_DATA_DIR");
  const std::string dir = env && *env ? env : EDGEVIO_DEFAULT_DATA_DIR;
  return fs::is_directory(dir) ? dir : "";
}

std::string sharedDataPath(const std::string& subpath) {
  const std::string dir = sharedDataDir();
  if (dir.empty()) return "";
  const fs::path p = fs::path(dir) / subpath;
  return fs::exists(p) ? p.string() : "";
}

std::string sourceDir() { return EDGEVIO_SOURCE_DIR; }

std::string sharedRender(const std::string& key, const std::function<void(const std::string& out_dir)>& render) {
  // The stamp of this program's file: size and modification time.
  const fs::path exe = fs::read_symlink("/proc/self/exe");
  const auto mtime = fs::last_write_time(exe).time_since_epoch().count();
  const std::string stamp = exe.filename().string() + "-" + std::to_string(fs::file_size(exe)) + "-" + std::to_string(mtime);
  const fs::path cache = fs::path(EDGEVIO_TEST_RENDER_CACHE), dir = cache / stamp, done = dir / (key + ".done");
  fs::create_directories(dir);
  // One process renders while the others wait on the lock; a render a
  // crashed process left half-written has no .done and is made again.
  const int lock = ::open((dir / (key + ".lock")).c_str(), O_CREAT | O_RDWR, 0644);
  if (lock < 0 || ::flock(lock, LOCK_EX) != 0) throw std::runtime_error("cannot lock " + (dir / key).string());
  if (!fs::exists(done)) {
    // Renders of earlier builds of this program are never read again.
    for (const auto& old : fs::directory_iterator(cache))
      if (old.path().filename().string().rfind(exe.filename().string() + "-", 0) == 0 && old.path() != dir)
        fs::remove_all(old.path());
    fs::remove_all(dir / key);
    render((dir / key).string());
    std::ofstream(done) << "rendered\n";
  }
  ::close(lock);
  return (dir / key).string();
}

TempDir::TempDir() {
  static std::atomic<int> counter{0};
  path_ = (fs::temp_directory_path() /
           ("edgevio_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++)))
              .string();
  fs::remove_all(path_);
  fs::create_directories(path_);
}

TempDir::~TempDir() {
  std::error_code ec;
  fs::remove_all(path_, ec);
}

std::string TempDir::write(const std::string& name, const std::string& text) const {
  const fs::path p = fs::path(path_) / name;
  fs::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << text;
  return p.string();
}

std::string readFile(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
}

Eigen::MatrixXd numericJacobian(const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& f,
                                const Eigen::VectorXd& x, double h) {
  const Eigen::VectorXd f0 = f(x);
  Eigen::MatrixXd J(f0.size(), x.size());
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    Eigen::VectorXd xp = x, xm = x;
    xp(i) += h;
    xm(i) -= h;
    J.col(i) = (f(xp) - f(xm)) / (2.0 * h);
  }
  return J;
}

void expectJacobianNear(const Eigen::MatrixXd& analytic, const Eigen::MatrixXd& numeric, double tol,
                        const std::string& what) {
  ASSERT_EQ(analytic.rows(), numeric.rows()) << what;
  ASSERT_EQ(analytic.cols(), numeric.cols()) << what;
  const double err = (analytic - numeric).cwiseAbs().maxCoeff();
  EXPECT_LE(err, tol) << what << "\nanalytic:\n" << analytic << "\nnumeric:\n" << numeric;
}

void expectContainsAll(const std::string& text, const std::vector<std::string>& fragments) {
  for (const std::string& f : fragments) EXPECT_NE(text.find(f), std::string::npos) << "'" << f << "' not in:\n" << text;
}

}  // namespace edgevio::test
