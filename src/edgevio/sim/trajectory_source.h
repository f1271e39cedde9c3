#pragma once
// Where a simulated motion comes from: a trajectory file (TUM or EuRoC ground
// truth, e.g. the real ones in shared/data/trajectories) or a built-in
// scenario. Either way the result is a SplineTrajectory, so images, IMU and the
// written ground truth all come from one smooth motion.
#include <cstdint>
#include <string>
#include <vector>

#include "edgevio/io/trajectory_io.h"
#include "edgevio/sim/spline_trajectory.h"

namespace edgevio::sim {

/// Built-in scenarios; each starts with `static_start_s` of standstill.
///  hover:      small drifts and slow yaw around a point;
///  figure8:    a 3 m x 2 m figure eight, banking, 12 s period;
///  aggressive: a fast figure eight with rotation-rate peaks >= 5 rad/s and
///              accelerations >= 2 g;
///  throw:      the paper's experiment: walking a 2 m-radius loop, the rig is
///              thrown up (0.7 s flights, a full roll while airborne) and caught
///              every 3 s.
const std::vector<std::string>& scenarioNames();

/// Samples a scenario at 200 Hz. `T_b_c` orients the rig so that the camera
/// looks horizontally (camera y down) when level. Throws InputError for an unknown name.
io::Trajectory scenarioSamples(const std::string& name, double duration_s, double static_start_s,
                               const geometry::SE3& T_b_c);

/// The scenarios' time origin (arbitrary; a plausible Unix time in ns).
constexpr std::int64_t kScenarioStartNs = 1600000000000000000LL;

/// Fits a spline with knot spacing `knot_dt_s` through the samples over
/// [begin_ns, end_ns]. Throws InputError (naming `source`) when the samples do
/// not cover the span or have a gap longer than `max_gap_s` inside it.
SplineTrajectory fitSpline(const io::Trajectory& samples, std::int64_t begin_ns, std::int64_t end_ns,
                           double knot_dt_s, double max_gap_s, const std::string& source);

}  // namespace edgevio::sim
