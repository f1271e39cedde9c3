#include <cmath>
#include <ostream>

#include "edgevio/cli/commands.h"
#include "edgevio/cli/progress.h"
#include "edgevio/common/error.h"
#include "edgevio/config/config.h"
#include "edgevio/sim/simulator.h"

namespace edgevio::cli {

int simulate(const SimulateArgs& a, std::ostream& out, std::ostream& err) {
  try {
    Config config = a.config.empty() ? Config{} : loadConfig(a.config);
    if (a.vignetting >= 0) config.sim.vignetting = a.vignetting;
    if (a.stereo_mismatch >= 0) config.sim.stereo_brightness_mismatch = a.stereo_mismatch;
    if (!std::isnan(a.imu_time_offset_ms)) config.sim.imu_time_offset_ms = a.imu_time_offset_ms;
    if (a.noise != "on" && a.noise != "off") throw InputError("--noise must be on or off");
    sim::SimRequest r;
    r.out_dir = a.out;
    r.trajectory_file = a.trajectory;
    r.scenario = a.scenario;
    r.start_s = a.start_s;
    if (a.duration_s >= 0) r.duration_s = a.duration_s;
    r.seed = a.seed;
    r.imu = a.imu;
    r.noise = a.noise == "on";
    r.blur_ms = a.blur_ms;
    r.exposure_changes = a.exposure_changes;
    r.drop_rate = a.drop_rate;
    r.skip = a.skip;
    r.calib = a.calib;
    for (const std::string& spec : a.faults) r.faults.push_back(sim::parseFault(spec));
    Progress progress("stereo frames rendered", Progress::stderrIsTerminal());
    const sim::SimSummary s =
        sim::simulate(r, config.sim, [&](std::size_t done, std::size_t total) { progress.update(done, total); });
    out << "wrote " << a.out << "/mav0: " << s.frames << " stereo frames (" << s.dropped_cam1 + s.fault_dropped[1]
        << " cam1 and " << s.fault_dropped[0] << " cam0 images dropped), " << s.imu_samples << " IMU samples, " << s.duration_s << " s\n";
    if (s.position_steps_removed > 0)
      out << "trajectory: " << s.position_steps_removed
          << " position steps removed (tracker glitches; sim.trajectory_max_accel_mps2 = " << config.sim.trajectory_max_accel_mps2
          << ", 0 keeps the file as is)\n";
    out << "time: " << s.wall_s << " s wall: setup " << s.setup_s << " s, then "
        << static_cast<double>(s.frames) / std::max(s.wall_s - s.setup_s, 1e-9) << " stereo frames/s (per-camera totals: ray casting "
        << s.render_s << " s, image writing " << s.write_s << " s)\n";
    return kExitOk;
  } catch (const InputError& e) {
    err << "error: " << e.what() << "\n";
    return kExitError;
  }
}

}  // namespace edgevio::cli
