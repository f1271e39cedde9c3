#pragma once
// One frame at a time through the system (METHOD.md §1): tracking, then (in
// the IMU modes) the estimator. The stage code both the offline and the
// real-time drivers call; it owns the tracker and the estimator and talks to
// them through their plain results (FrameTrack, EstimatorUpdate).
//   edge-only: the tracker's causal pose, the gyroscope for the rotation guess.
//   edge+imu:  the IMU predicts every frame (the alignment's initial guess),
//              the tracking link passes the external check into the window,
//              the window is solved and marginalised, and the newest state
//              is the frame's pose. A rejected link makes the frame a keyframe.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "edgevio/camera/stereo_rectifier.h"
#include "edgevio/config/config.h"
#include "edgevio/estimator/vio_estimator.h"
#include "edgevio/imu/gyro_integration.h"
#include "edgevio/tracking/edge_tracker.h"

namespace edgevio::pipeline {

/// Everything that happened to one frame (a row of frames.csv).
struct FrameResult {
  tracking::FrameTrack track;
  geometry::SE3 T_w_b;                   ///< the causal pose estimate of the frame
  bool estimator_used = false;
  std::optional<imu::NavState> state;    ///< the newest window state (velocity, biases) when the estimator ran
  estimator::EstimatorUpdate estimator;
  std::string external_check = "-";      ///< accepted | rejected | - (no link offered)
  estimator::ExternalCheckResult external;
  bool forced_keyframe = false;          ///< became a keyframe because its link was rejected or the keyframe left the window
  std::string event;                     ///< a reset or an IMU gap, for the log
};

bool isImuMode(const std::string& mode);
/// Empty when `mode` is one `edgevio run` accepts, else the message naming the choices.
std::string checkMode(const std::string& mode);

class Odometry {
 public:
  /// `imu` must outlive the object.
  Odometry(const std::string& mode, const Config& config, const camera::StereoRig& rig,
           const camera::StereoRectifier& rectifier, const std::vector<io::ImuSample>& imu,
           const imu::StaticInit& init);

  FrameResult process(const tracking::StereoFrame& frame);

  bool lost() const { return tracker_.lost(); }
  std::size_t resets() const { return resets_; }

 private:
  FrameResult processEdgeOnly(const tracking::StereoFrame& frame);
  FrameResult processEdgeImu(const tracking::StereoFrame& frame);
  void restart(std::int64_t t_ns, imu::NavState x, bool static_start);

  std::string mode_;
  Config config_;
  const std::vector<io::ImuSample>& imu_;
  imu::StaticInit init_;
  tracking::EdgeTracker tracker_;
  estimator::VioEstimator estimator_;
  std::int64_t t_first_ = -1, t_prev_ = -1;
  std::size_t resets_ = 0;
};

}  // namespace edgevio::pipeline
