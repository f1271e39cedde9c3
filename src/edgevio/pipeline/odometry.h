#pragma once
// One frame at a time through the system (METHOD.md §1): tracking, the
// keyframe policy, the estimator, then loop closure on new keyframes. The
// stage code both the offline and the real-time drivers call. It owns the
// keyframes (one KeyframeStore), asks the tracker for tracks and the
// estimator for states, and returns one FrameRecord per frame.
//   edge-only:     the tracker's pose; the gyroscope guesses the rotation.
//   edge+loop:     the window as a pose graph of tracking and loop links
//                  (no IMU links); the gyroscope guesses the rotation.
//   edge+imu:      the IMU predicts every frame (the alignment's initial
//                  guess), tracking links pass the external check into the
//                  window, which is solved and marginalised; the newest state
//                  is the frame's pose.
//   edge+imu+loop: the full system.
// In the window's modes every new keyframe is also linked back into the
// keyframes before it (loop/back_links.h). Marginalisation and a new
// keyframe's depth (block matching) run once the frame's pose is out; so do,
// in real time only, the window's Gauss-Newton iterations (by default all of
// them: the pose is the newest state solved alone with the rest of the window
// held; estimator.realtime_pose_iterations) and the keyframe's loop closure
// and back links, whose links then join the next frame's solve instead of
// this one's: a pose waits for no work that does not change it, and in real
// time for none that changes it little.
//
// The keyframe policy (METHOD.md §3, §5): a frame becomes a keyframe when
// tracking votes for it (its alignment failed, or edge counts, reference
// points or visibility say so), when the estimator refuses its link, when
// the keyframe it was tracked against leaves the window, or when the window
// restarts at it. When its alignment to the keyframe fails, the previous
// frame (already tracked, closer to it) becomes the keyframe first and the
// frame is aligned again.
#include <opencv2/core.hpp>

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "edgevio/config/config.h"
#include "edgevio/estimator/vio_estimator.h"
#include "edgevio/imu/gyro_integration.h"
#include "edgevio/pipeline/frame_record.h"
#include "edgevio/pipeline/keyframe_store.h"
#include "edgevio/pipeline/loss_monitor.h"
#include "edgevio/pipeline/mode.h"
#include "edgevio/tracking/edge_tracker.h"

namespace edgevio::pipeline {

class Odometry {
 public:
  /// `tracker` and `imu` must outlive the object. T_b_c: body → the camera
  /// the tracker's links are measured in. `realtime`: loop closure's time
  /// budget (loop.realtime_max_ms) applies; offline only its attempt counts
  /// bound the work, so that the result does not depend on the machine. In
  /// real time a new keyframe's loop closure and back links also wait until
  /// its pose is out. `pictures`: each record carries what its alignment
  /// picture is drawn from (FrameRecord::picture).
  Odometry(Mode mode, const Config& config, const tracking::Tracker& tracker, const geometry::SE3& T_b_c,
           const imu::ImuNoise& noise, const std::vector<imu::ImuSample>& imu, const imu::StaticInit& init,
           bool realtime = false, bool pictures = false);

  /// The frame's pyramid must be built with the config's vision options
  /// (tracking::prepareFrame); a driver may do that on another thread.
  /// `posed` is called as soon as the record's pose and status are final,
  /// before marginalisation and a new keyframe's depth (and in real time its
  /// loop closure and back links, whose links enter the window with the
  /// next frame): what a consumer of poses waits for.
  FrameRecord process(tracking::PreparedFrame frame, const std::function<void(const FrameRecord&)>& posed = {});

 private:
  /// A frame tracked but not made a keyframe: it becomes the keyframe when
  /// the next frame fails to align to the old one, or when the window needs one.
  struct Previous {
    tracking::PreparedFrame frame;
    geometry::SE3 T_w_b;  ///< the pose tracking gave it
  };

  /// A frame's pose from tracking (the prediction's when its alignment
  /// failed), and tracking's vote for making it a keyframe.
  struct Tracked {
    geometry::SE3 T_w_b;
    tracking::KeyframeReason vote = tracking::KeyframeReason::kNone;
  };

  void processWithoutWindow(tracking::PreparedFrame frame, FrameRecord* r);
  void startWindow(std::int64_t t_ns, FrameRecord* r);
  void processInWindow(tracking::PreparedFrame frame, FrameRecord* r);
  void bridgeImuGap(tracking::PreparedFrame frame, FrameRecord* r);
  void restartAfterImuGap(FrameRecord* r);

  /// The gyroscope's rotation since the previous frame on T_w_b_last, or
  /// without it (no reading, a gap) the constant-velocity prediction.
  tracking::Prediction gyroPrediction(const geometry::SE3& T_w_b_last, std::int64_t t_ns) const;
  tracking::Prediction constantVelocityPrediction(std::int64_t t_ns) const;
  /// Aligns the frame to the current keyframe, promoting the previous frame when that fails.
  Tracked track(const tracking::PreparedFrame& frame, const tracking::Prediction& p, FrameRecord* r);
  /// Offers the frame's tracking link to the window; true when it entered.
  bool offerLink(const tracking::PreparedFrame& frame, FrameRecord* r);
  /// Makes the frame a keyframe (or keeps it as the previous frame when `why` is kNone).
  void decideKeyframe(tracking::PreparedFrame frame, const geometry::SE3& T_w_b, tracking::KeyframeReason why, FrameRecord* r);
  void addKeyframe(tracking::PreparedFrame frame, const geometry::SE3& T_w_b, tracking::KeyframeReason why, FrameRecord* r);
  /// Makes the previous frame the keyframe; false when there is none.
  bool promotePrevious(tracking::KeyframeReason why, FrameRecord* r);
  /// Solves the window (the newest state is the frame's pose; in real time
  /// after estimator.realtime_pose_iterations); handles a restart.
  void solveWindow(bool link_good, const geometry::SE3& restart_pose, FrameRecord* r);
  /// When the estimate blew up (r->estimator says why): the window restarted at this frame.
  bool restartedAfterBlowUp(FrameRecord* r);
  /// Two-way marginalisation when the window is full; handles the keyframe leaving it.
  void marginalize(bool link_good, FrameRecord* r);
  /// After the window (re)started at t_ns: that frame is its only keyframe.
  void keyframeForRestart(std::int64_t t_ns, FrameRecord* r);

  /// The frame's work after its pose is out: the solve's remaining
  /// iterations, marginalisation, then linkNewKeyframe.
  void finishFrame(FrameRecord* r);
  /// The current keyframe's data (makeKeyframeData), and the loop closure
  /// and back links owed to it.
  void linkNewKeyframe(FrameRecord* r);
  /// The newest keyframe's images and depth, if still to be made.
  void makeKeyframeData(FrameRecord* r);
  void closeLoops(FrameRecord* r);
  void linkBack(const geometry::SE3& T_w_b, FrameRecord* r);

  geometry::SE3 keyframePose(const Keyframe& k) const;
  std::optional<geometry::SO3> gyroRotation(std::int64_t t0, std::int64_t t1, const Vec3& bias) const;
  /// A camera time on the IMU's clock (the window's time offset estimate).
  std::int64_t imuTime(std::int64_t t_ns) const;
  /// The loss monitor's motion signals of the frame's pose: implied speed and
  /// acceleration, the gyroscope's and the accelerometer's disagreement.
  void recordMotion(FrameRecord* r) const;
  bool windowed() const { return estimator_.has_value(); }
  /// Body → camera: the window's estimate when it corrects the calibration's.
  geometry::SE3 cameraExtrinsics() const { return windowed() ? estimator_->cameraExtrinsics() : T_b_c_; }

  Mode mode_;
  Config config_;
  const tracking::Tracker& tracker_;
  const std::vector<imu::ImuSample>& imu_;
  imu::StaticInit init_;
  geometry::SE3 T_b_c_;
  bool realtime_;
  bool pictures_;
  LossMonitor loss_;
  cv::Mat previous_image_;  ///< the previous frame's level-0 image (frozen-image check)
  std::optional<estimator::VioEstimator> estimator_;  ///< the window's modes
  KeyframeStore keyframes_;
  std::optional<Previous> previous_;
  /// The newest keyframe's frame until its data is made (makeKeyframeData).
  std::optional<tracking::PreparedFrame> unmade_keyframe_;
  /// What finishFrame owes the frame just solved.
  struct AfterPose {
    std::optional<geometry::SE3> finish_solve_restarting_at;  ///< the solve's remaining iterations; where a blow-up restarts
    std::optional<bool> marginalize_after_good_link;  ///< marginalise; the two-way rule's "was the frame's link good"
    bool loops = false;                               ///< loop closure of the current keyframe
    std::optional<geometry::SE3> back_links_from;     ///< its back links, checked against its tracked pose
  } after_pose_;
  geometry::SE3 T_w_b_last_, T_w_b_before_last_;  ///< the poses of the last two frames (at t_prev_, t_before_last_)
  std::int64_t t_first_ = -1, t_prev_ = -1, t_before_last_ = -1;
};

}  // namespace edgevio::pipeline
