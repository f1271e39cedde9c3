#include <cmath>
#include <ostream>

#include "edgevio/cli/commands.h"
#include "edgevio/common/error.h"
#include "edgevio/common/json.h"
#include "edgevio/config/config.h"
#include "edgevio/common/time.h"
#include "edgevio/io/bag_sequence.h"
#include "edgevio/io/sequence.h"

namespace edgevio::cli {

int info(const InfoArgs& args, std::ostream& out, std::ostream& err) {
  try {
    const Config config = args.config.empty() ? Config{} : loadConfig(args.config);
    const std::unique_ptr<io::Sequence> seq = io::openSequence(args.source, config.dataset);
    // Decode every pair once: frames that fail to decode are found and counted.
    std::size_t stereo_pairs = 0;
    for (std::size_t i = 0; i < seq->frameCount(); ++i)
      if (seq->leftImage(i) && !seq->rightImageLoader(i)().empty()) ++stereo_pairs;
    const auto& imu = seq->imu();
    const double imu_span = toSeconds(imu.back().t_ns - imu.front().t_ns);
    JsonWriter j(out);
    j.beginObject();
    j.key("dataset").value(seq->location());
    for (int cam = 0; cam < 2; ++cam) j.key("cam" + std::to_string(cam) + "_frames").value(seq->cameraFrames(cam));
    j.key("stereo_pairs").value(stereo_pairs);
    j.key("imu_samples").value(imu.size());
    j.key("imu_rate_hz").value(std::round(static_cast<double>(imu.size() - 1) / imu_span * 100.0) / 100.0);
    j.key("duration_s").value(seq->frameCount() < 2 ? 0.0 : toSeconds(seq->frameTime(seq->frameCount() - 1) - seq->frameTime(0)));
    j.key("groundtruth_poses").value(seq->groundTruth().size());
    if (const auto* bag = dynamic_cast<const io::BagSequence*>(seq.get())) {
      const io::BagTopics& t = bag->topics();
      j.key("topics").beginObject();
      j.key("cam0").value(t.cam0).key("cam1").value(t.cam1).key("imu").value(t.imu).key("groundtruth").value(t.groundtruth);
      j.endObject();
    }
    j.key("warnings").beginArray();
    for (const auto& w : seq->warnings()) j.value(w);
    j.endArray();
    j.endObject();
    return kExitOk;
  } catch (const InputError& e) {
    err << "error: " << e.what() << "\n";
    return kExitError;
  }
}

}  // namespace edgevio::cli
