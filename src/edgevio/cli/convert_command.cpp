#include <ostream>

#include "edgevio/cli/commands.h"
#include "edgevio/cli/flags.h"
#include "edgevio/cli/progress.h"
#include "edgevio/common/error.h"
#include "edgevio/config/config.h"
#include "edgevio/io/bag_export.h"

namespace edgevio::cli {

int convert(const ConvertArgs& a, std::ostream& out, std::ostream& err) {
  try {
    io::BagExportOptions options;
    parseFlagChoice("--compression", a.compression, io::kBagCompressionChoices, &options.compression);
    parseFlagChoice("--images", a.images, io::kBagImagesChoices, &options.images);
    const std::unique_ptr<io::Sequence> seq = io::openSequence(a.source, Config{}.dataset);
    Progress progress("stereo frames written", Progress::stderrIsTerminal());
    const io::BagExport e =
        io::exportBag(*seq, a.out, options, [&](std::size_t done, std::size_t total) { progress.update(done, total); });
    out << "wrote " << a.out << ": " << e.stereo_frames << " stereo frames on " << e.topics.cam0 << " and " << e.topics.cam1 << ", "
        << e.imu_messages << " IMU messages on " << e.topics.imu;
    if (e.groundtruth_messages > 0) out << ", " << e.groundtruth_messages << " ground-truth poses on " << e.topics.groundtruth;
    out << "; calibration beside it: " << e.camchain_yaml << ", " << e.imu_yaml << "\n";
    return kExitOk;
  } catch (const InputError& e) {
    err << "error: " << e.what() << "\n";
    return kExitError;
  }
}

}  // namespace edgevio::cli
