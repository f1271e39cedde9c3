#include <fstream>
#include <ostream>

#include "edgevio/cli/commands.h"
#include "edgevio/cli/progress.h"
#include "edgevio/common/error.h"
#include "edgevio/config/config.h"
#include "edgevio/doctor/doctor.h"
#include "edgevio/io/sequence.h"

namespace edgevio::cli {

int doctor(const DoctorArgs& args, std::ostream& out, std::ostream& err) {
  try {
    if (args.format != "text" && args.format != "json") throw InputError("--format must be text or json");
    const Config config = args.config.empty() ? Config{} : loadConfig(args.config);
    const std::unique_ptr<io::Sequence> seq = io::openSequence(args.source, config.dataset);
    Progress progress("frames examined", Progress::stderrIsTerminal());
    const doctor::DoctorReport report =
        doctor::diagnose(*seq, config, [&](std::size_t done, std::size_t total) { progress.update(done, total); });
    if (!args.html.empty()) {
      std::ofstream page(args.html);
      if (!page) throw InputError(args.html, 0, "cannot write the page (does the folder exist?)");
      page << doctor::htmlPage(report);
    }
    if (args.format == "json") doctor::writeJson(out, report);
    else doctor::writeText(out, report);
    if (!args.html.empty() && args.format == "text") out << "plots: " << args.html << "\n";
    return kExitOk;
  } catch (const InputError& e) {
    err << "error: " << e.what() << "\n";
    return kExitError;
  }
}

}  // namespace edgevio::cli
