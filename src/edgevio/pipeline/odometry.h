#pragma once
// One frame at a time through the system (METHOD.md §1): tracking, then the
// estimator, then local loop closure on new keyframes. The stage code both
// the offline and the real-time drivers call; it owns the tracker, the
// estimator and the keyframes in the window, and talks to them through their
// plain results (FrameTrack, EstimatorUpdate, LoopLink).
//   edge-only:     the tracker's causal pose; the gyroscope guesses the rotation.
//   edge+loop:     the window as a pose graph of tracking and loop links
//                  (no IMU links); the gyroscope guesses the rotation.
//   edge+imu:      the IMU predicts every frame (the alignment's initial
//                  guess), tracking links pass the external check into the
//                  window, which is solved and marginalised; the newest state
//                  is the frame's pose. A rejected link makes the frame a keyframe.
//   edge+imu+loop: the full system.
// In the window's modes every new keyframe is also linked back into the
// keyframes before it (loop/back_links.h).
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "edgevio/camera/stereo_rectifier.h"
#include "edgevio/config/config.h"
#include "edgevio/estimator/vio_estimator.h"
#include "edgevio/imu/gyro_integration.h"
#include "edgevio/loop/back_links.h"
#include "edgevio/loop/local_loop_closure.h"
#include "edgevio/tracking/edge_tracker.h"

namespace edgevio::pipeline {

/// Everything that happened to one frame (a row of frames.csv).
struct FrameResult {
  tracking::FrameTrack track;
  geometry::SE3 T_w_b;                   ///< the causal pose estimate of the frame
  std::optional<imu::NavState> state;    ///< the newest window state (velocity, biases) when the estimator ran
  estimator::EstimatorUpdate estimator;
  std::string external_check = "-";      ///< accepted | rejected | no reference | - (no link offered, or no IMU)
  estimator::ExternalCheckResult external;
  bool forced_keyframe = false;          ///< became a keyframe because its link was rejected or the keyframe left the window
  loop::BackLinkStats back;              ///< a new keyframe's links back into the keyframes before it
  int back_links_added = 0;              ///< ... of which entered the window (the estimator's loop check)
  bool loop_ran = false;                 ///< a new keyframe looked for loop closures
  loop::LoopStats loop;
  std::string event;                     ///< a reset or an IMU gap, for the log
};

bool isImuMode(const std::string& mode);
bool isLoopMode(const std::string& mode);
/// Empty when `mode` is one `edgevio run` accepts, else the message naming the choices.
std::string checkMode(const std::string& mode);

class Odometry {
 public:
  /// `imu` must outlive the object. `realtime`: time budgets (loop.max_ms)
  /// apply; offline only the attempt counts bound work, so that the result
  /// does not depend on the machine's speed.
  Odometry(const std::string& mode, const Config& config, const camera::StereoRig& rig,
           const camera::StereoRectifier& rectifier, const std::vector<io::ImuSample>& imu,
           const imu::StaticInit& init, bool realtime = false);

  /// The frame's pyramid must be built with the config's vision options
  /// (tracking::prepareFrame); a driver may do that on another thread.
  FrameResult process(tracking::PreparedFrame frame);

  bool lost() const { return tracker_.lost(); }
  std::size_t resets() const { return resets_; }
  std::size_t loopClosures() const { return loop_closures_; }
  std::size_t backLinks() const { return back_links_; }

 private:
  FrameResult processEdgeOnly(tracking::PreparedFrame frame);
  FrameResult processWindowed(tracking::PreparedFrame frame);
  FrameResult initializeWindow(tracking::PreparedFrame frame);
  void restart(std::int64_t t_ns, imu::NavState x, bool velocity_known, bool attitude_known);
  void closeLoops(FrameResult* r);
  void linkBack(const tracking::FrameTrack& t, FrameResult* r);
  std::optional<geometry::SO3> gyroRotation(std::int64_t t0, std::int64_t t1, const Vec3& bias) const;

  std::string mode_;
  bool inertial_, loop_;
  Config config_;
  const std::vector<io::ImuSample>& imu_;
  imu::StaticInit init_;
  geometry::SE3 T_b_c_;
  tracking::EdgeTracker tracker_;
  estimator::VioEstimator estimator_;
  std::map<std::int64_t, std::shared_ptr<const tracking::KeyframeData>> keyframes_;  ///< in the window, for loop closure
  std::int64_t t_first_ = -1, t_prev_ = -1;
  std::size_t resets_ = 0, loop_closures_ = 0, back_links_ = 0;
};

}  // namespace edgevio::pipeline
