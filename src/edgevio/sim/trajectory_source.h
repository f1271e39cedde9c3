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

/// Removes position steps from a recorded trajectory. Motion-capture and
/// laser-tracker ground truth holds steps the body never made: the EuRoC
/// machine-hall files have 30 (MH_04) and 62 (MH_03) of 1.3-130 mm (median
/// 4 mm), where the estimate behind the file was pulled to a new tracker fix;
/// a single-sample spike is a step out and one back. Images rendered along them disagree with
/// the replayed real IMU by ~0.1 m/s for a tenth of a second.
///
/// A sample-to-sample velocity (p_i − p_{i−1})/Δt_i further than
/// `max_accel_mps2`·Δt_i from the median of its ten neighbours (five each side;
/// for smooth motion that median is the velocity itself up to jerk·(5Δt)²), and
/// as far from the median of each side alone (so that a kink, a velocity jump
/// such as a scenario's throw, is kept), is
/// replaced by that median. Positions are re-summed from the increments, and
/// the offset r = p_file − p_summed is added back as its moving average over
/// `spread_s`: a step of s becomes a ramp of slope s/spread_s and the result
/// follows the file in the long run. Orientations are kept.
/// Returns the number of increments replaced; `max_accel_mps2` = 0: none.
int removePositionSteps(io::Trajectory& samples, double max_accel_mps2, double spread_s);

/// Fits a spline with knot spacing `knot_dt_s` through the samples over
/// [begin_ns, end_ns]. Throws InputError (naming `source`) when the samples do
/// not cover the span or have a gap longer than `max_gap_s` inside it.
SplineTrajectory fitSpline(const io::Trajectory& samples, std::int64_t begin_ns, std::int64_t end_ns,
                           double knot_dt_s, double max_gap_s, const std::string& source);

}  // namespace edgevio::sim
