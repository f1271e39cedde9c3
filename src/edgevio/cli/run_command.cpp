#include <ostream>

#include "edgevio/cli/commands.h"
#include "edgevio/cli/progress.h"
#include "edgevio/common/error.h"
#include "edgevio/config/config.h"
#include "edgevio/pipeline/run.h"
#include "edgevio/view/live_view.h"
#include "edgevio/view/recording.h"

#include <memory>

namespace edgevio::cli {

int run(const RunArgs& a, std::ostream& out, std::ostream& err) {
  try {
    const Config config = a.config.empty() ? Config{} : loadConfig(a.config);
    const std::optional<pipeline::Mode> mode = pipeline::parseMode(a.mode);
    if (!mode) throw InputError("--mode: unknown mode '" + a.mode + "': use " + pipeline::kModeNames);
    pipeline::RunRequest r(a.source.path, a.out, *mode, a.skip);
    r.skip_offset = a.skip_offset;
    r.realtime = a.realtime;
    if (a.pictures_every < 0) throw InputError("--pictures-every must be >= 0 (0: no alignment pictures)");
    r.picture_stride = a.pictures_every;
    r.calib = a.source.calib;
    r.topics = a.source.topics;
    Progress progress("frames", Progress::stderrIsTerminal());
    pipeline::RunObserver observer;
    observer.progress = [&](std::size_t done, std::size_t total, double seq_s) { progress.update(done, total, seq_s); };
    observer.event = [&](const std::string& event) { err << "warning: " << event << "\n"; };
    std::unique_ptr<view::Recording> recording;
    std::unique_ptr<view::LiveView> live;
    observer.opened = [&](const io::Sequence& sequence) {
      if (!a.mcap.empty()) recording = std::make_unique<view::Recording>(a.mcap, sequence);
      if (a.view_port >= 0) {
        live = std::make_unique<view::LiveView>(a.view_port, a.mode, sequence.name());
        err << "viewer: http://127.0.0.1:" << live->port() << "/ (open it in a browser while the run goes)" << std::endl;
      }
    };
    observer.frame = [&](const pipeline::FrameRecord& record, const std::vector<std::uint8_t>& jpeg) {
      if (recording) recording->write(record, jpeg);
      if (live) live->frame(record, jpeg);
    };
    const pipeline::RunSummary s = pipeline::run(r, config, observer);
    if (recording) recording->close();
    if (live) live->finish(s);
    out << "mode " << a.mode << ": " << s.frames << " frames, " << s.keyframes << " keyframes, "
        << s.self_check_failures << " self-check failures, " << s.external_check_rejections
        << " external-check rejections, " << (a.realtime ? std::to_string(s.dropped_frames) + " frames dropped (real time), " : std::string())
        << s.loop_closures << " loop closures, " << s.estimator_resets << " estimator resets, " << s.wall_s << " s wall, real-time factor "
        << s.realtime_factor << (s.lost_intervals.empty() ? std::string() : ", " + s.lossText())
        << (s.failed ? ", FAILED: " + s.failure : std::string()) << "\n"
        << "wrote " << a.out << "/{trajectory_tum.txt, trajectory.csv, frames.csv, summary.json, config.yaml"
        << (a.pictures_every > 0 ? ", alignment/" : "") << "}" << (a.mcap.empty() ? "" : " and " + a.mcap) << "\n";
    return s.failed ? kExitError : kExitOk;
  } catch (const InputError& e) {
    err << "error: " << e.what() << "\n";
    return kExitError;
  }
}

}  // namespace edgevio::cli
