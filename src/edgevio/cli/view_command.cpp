#include <filesystem>
#include <ostream>

#include "edgevio/cli/commands.h"
#include "edgevio/common/error.h"
#include "edgevio/config/config.h"
#include "edgevio/view/run_view.h"

namespace edgevio::cli {

int view(const ViewArgs& a, std::ostream& out, std::ostream& err) {
  try {
    namespace fs = std::filesystem;
    if (!fs::is_directory(a.run_dir)) throw InputError(a.run_dir, 0, "run folder not found");
    // The run's own evaluation settings (its config.yaml), as `edgevio eval` would use them.
    const fs::path config_yaml = fs::path(a.run_dir) / "config.yaml";
    const Config config = fs::exists(config_yaml) ? loadConfig(config_yaml.string()) : Config{};
    const std::string page = a.out.empty() ? (fs::path(a.run_dir) / "view.html").string() : a.out;
    std::vector<std::string> notes;
    view::writeRunView(a.run_dir, page, config.eval, &notes);
    for (const std::string& n : notes) err << "note: " << n << "\n";
    out << "wrote " << page << " (open it in a browser; it needs no server or network)\n";
    return kExitOk;
  } catch (const InputError& e) {
    err << "error: " << e.what() << "\n";
    return kExitError;
  }
}

}  // namespace edgevio::cli
