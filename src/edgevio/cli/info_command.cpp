#include <cmath>
#include <ostream>

#include "edgevio/cli/commands.h"
#include "edgevio/common/error.h"
#include "edgevio/common/json.h"
#include "edgevio/config/config.h"
#include "edgevio/io/euroc_dataset.h"

namespace edgevio::cli {

int info(const InfoArgs& args, std::ostream& out, std::ostream& err) {
  try {
    const Config config = args.config.empty() ? Config{} : loadConfig(args.config);
    io::EurocDataset dataset(args.dataset, config.dataset);
    // Decode every pair once: frames that fail to decode are found and counted.
    std::size_t stereo_pairs = 0;
    for (std::size_t i = 0; i < dataset.stereoPairs().size(); ++i)
      if (dataset.loadStereo(i)) ++stereo_pairs;

    JsonWriter j(out);
    j.beginObject();
    j.key("dataset").value(dataset.mav0());
    for (int cam = 0; cam < 2; ++cam)
      j.key("cam" + std::to_string(cam) + "_frames")
          .value(dataset.cameraRows(cam) - dataset.unreadableImages(cam));
    j.key("stereo_pairs").value(stereo_pairs);
    j.key("imu_samples").value(dataset.imu().size());
    j.key("imu_rate_hz").value(std::round(dataset.imuRateHz() * 100.0) / 100.0);
    j.key("duration_s").value(dataset.durationSeconds());
    j.key("groundtruth_poses").value(dataset.groundTruth().size());
    j.key("warnings").beginArray();
    for (const auto& w : dataset.warnings()) j.value(w);
    j.endArray();
    j.endObject();
    return kExitOk;
  } catch (const InputError& e) {
    err << "error: " << e.what() << "\n";
    return kExitError;
  }
}

}  // namespace edgevio::cli
