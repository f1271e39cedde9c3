#pragma once
// Tracking (METHOD.md §3): a frame aligned to a keyframe from a prediction of
// its pose. The tracker holds no state: which keyframe a frame is aligned to,
// and when a frame becomes one, is the pipeline's keyframe policy
// (pipeline/odometry.h). It answers three questions:
//   makeKeyframe   a frame's reference points with stereo depth (block matching);
//   track          the frame's pose relative to a keyframe, with the checks of
//                  the alignment against the prediction;
//   the visual keyframe votes of the result (edge counts, points, visibility).
#include <opencv2/core.hpp>

#include <functional>
#include <memory>
#include <optional>

#include "edgevio/camera/stereo_rectifier.h"
#include "edgevio/tracking/edge_alignment.h"
#include "edgevio/tracking/tracking_options.h"
#include "edgevio/vision/keyframe_depth.h"

namespace edgevio::tracking {

/// An image, or how to get it. Only keyframes need the right image (block
/// matching, about one frame in ten), so a driver may hand over a loader that
/// decodes and rectifies it on first use: that halves the decoding work.
class LazyImage {
 public:
  LazyImage() = default;
  LazyImage(cv::Mat image) : image_(std::move(image)) {}  // NOLINT: an image is its own loader
  explicit LazyImage(std::function<cv::Mat()> load) : load_(std::move(load)) {}
  /// The image, loaded on the first call; empty when loading failed.
  const cv::Mat& get() const {
    if (load_) {
      image_ = load_();
      load_ = nullptr;
    }
    return image_;
  }

 private:
  mutable cv::Mat image_;
  mutable std::function<cv::Mat()> load_;
};

/// A rectified stereo pair at full resolution.
struct StereoFrame {
  std::int64_t t_ns = 0;
  cv::Mat left;
  LazyImage right;
};

/// A stereo frame with its left edge pyramid built: what tracking consumes.
/// The pyramid depends on the image alone, so a pipeline can build it ahead
/// of tracking, on another thread.
struct PreparedFrame {
  std::int64_t t_ns = 0;
  LazyImage right;  ///< full resolution; block matching uses it if the frame becomes a keyframe
  vision::EdgePyramid pyramid;
};

PreparedFrame prepareFrame(const StereoFrame& frame, const camera::StereoRectifier& rectifier,
                           const vision::VisionOptions& vision);

/// A keyframe's images as alignment needs them: its edge pyramid and its
/// reference points with stereo depth. Immutable once made; shared by
/// tracking, back links and loop closure.
struct KeyframeData {
  std::int64_t t_ns = 0;
  vision::EdgePyramid pyramid;
  vision::KeyframeDepth depth;
  bool right_image_unreadable = false;  ///< its right image did not decode: it has no reference points
  int referencePoints() const { return depth.points.empty() ? 0 : static_cast<int>(depth.points[0].size()); }
};

/// Why a frame became a keyframe.
enum class KeyframeReason {
  kNone,
  kFirstFrame,           ///< the sequence (or the visual tracking) starts here
  kSelfCheckFailed,      ///< its alignment failed; it keeps the prediction
  kEdgeCountChanged,     ///< level-0 or 1 edge counts of frame and keyframe differ by more than keyframe_edge_ratio
  kTooFewPoints,         ///< the keyframe has fewer than keyframe_min_points reference points
  kPointsLeavingView,    ///< fewer than keyframe_min_visible_ratio of them are in view
  kLinkRejected,         ///< the estimator's external check refused its link, or the keyframe was not in the window
  kKeyframeLeftWindow,   ///< marginalisation removed the keyframe: later links need a reference in the window
  kWindowRestart,        ///< the window restarted at this frame (IMU gap, estimate blew up, first IMU reading)
};
inline constexpr options::Choice<KeyframeReason> kKeyframeReasonChoices[] = {
    {KeyframeReason::kNone, "-", "not a keyframe"},
    {KeyframeReason::kFirstFrame, "first frame", "tracking starts here"},
    {KeyframeReason::kSelfCheckFailed, "self check failed", "its alignment failed; its pose is the prediction"},
    {KeyframeReason::kEdgeCountChanged, "edge count changed", "level-0 or 1 edge counts differ by more than tracking.keyframe_edge_ratio"},
    {KeyframeReason::kTooFewPoints, "too few reference points", "the keyframe has fewer than tracking.keyframe_min_points"},
    {KeyframeReason::kPointsLeavingView, "points leaving the view", "fewer than tracking.keyframe_min_visible_ratio of them in view"},
    {KeyframeReason::kLinkRejected, "link rejected", "the external check refused its link, or its keyframe had left the window"},
    {KeyframeReason::kKeyframeLeftWindow, "keyframe left the window", "marginalisation removed the keyframe it was tracked against"},
    {KeyframeReason::kWindowRestart, "window restart", "the estimator's window (re)started at this frame"}};

/// What of a pose prediction the tracker's checks may trust: nothing (a first
/// frame, no IMU), its rotation (gyroscope: the gyro check), or all of it (the
/// IMU's prediction from the window's newest state: the translation check too).
enum class PredictionReliability { kNone, kRotation, kPose };

/// The gyroscope's body rotation R_bref_bcur from a time [ns] to the frame being tracked.
using GyroSince = std::function<std::optional<geometry::SO3>(std::int64_t)>;

/// Where a frame is expected to be (METHOD.md §3, initial guess).
struct Prediction {
  geometry::SE3 T_w_b;
  PredictionReliability reliable = PredictionReliability::kNone;
  /// IMU modes: the gyroscope alone since a keyframe, the alignment's rotation prior (empty: none).
  GyroSince gyro_since;
  /// Body → rectified left camera when the window corrects the calibration's
  /// (estimator.estimate_cam_imu_rotation, _translation); empty: the calibration's.
  std::optional<geometry::SE3> T_b_c;
  /// How far [m] the frame's camera can be from the predicted one by the motion
  /// model (a constant-velocity prediction: tracking.constant_velocity_max_accel_mps2
  /// over the interval); empty: no bound. An alignment beyond it is redone
  /// from the prediction on the fine levels and fails if it stays beyond.
  std::optional<double> max_translation_m;
};

/// Which check of an alignment against its prediction re-aligned it.
enum class PredictionCheck { kNone, kGyro, kTranslation, kMotion };
inline constexpr options::Choice<PredictionCheck> kPredictionCheckChoices[] = {
    {PredictionCheck::kNone, "-", "the first alignment was kept"},
    {PredictionCheck::kGyro, "gyro", "its rotation was far from the gyroscope's: re-aligned on the fine levels"},
    {PredictionCheck::kTranslation, "translation", "its translation was far from the IMU's: re-aligned, the closer fit kept"},
    {PredictionCheck::kMotion, "motion",
     "beyond the motion model's reach from a prediction without the IMU: re-aligned, failed if still beyond"}};

/// A frame aligned to a keyframe.
struct Track {
  AlignmentResult alignment;
  PredictionCheck check = PredictionCheck::kNone;
  geometry::SE3 T_w_b;  ///< the frame's pose from the alignment (meaningful when it passed the self check)
  /// The visual reasons for a new keyframe (METHOD.md §3): edge counts, points, visibility; kNone when the
  /// alignment failed (the policy decides then).
  KeyframeReason keyframe_vote = KeyframeReason::kNone;
  bool passed() const { return alignment.self_check_passed; }
};

/// The front end as the pipeline sees it. An interface so that the pipeline
/// can be tested on synthetic tracks, without images.
class Tracker {
 public:
  virtual ~Tracker() = default;
  /// The frame's reference points from stereo block matching; the frame's pyramid moves into the keyframe.
  virtual std::shared_ptr<const KeyframeData> makeKeyframe(PreparedFrame frame) const = 0;
  /// Aligns `frame` to `keyframe`, whose body pose is T_w_b_keyframe, from the prediction.
  virtual Track track(const PreparedFrame& frame, const KeyframeData& keyframe, const geometry::SE3& T_w_b_keyframe,
                      const Prediction& prediction) const = 0;
};

/// Edge alignment (METHOD.md §3) behind the Tracker interface.
class EdgeTracker final : public Tracker {
 public:
  EdgeTracker(const camera::StereoRectifier& rectifier, const vision::VisionOptions& vision,
              const AlignmentOptions& alignment, const TrackingOptions& tracking);
  std::shared_ptr<const KeyframeData> makeKeyframe(PreparedFrame frame) const override;
  Track track(const PreparedFrame& frame, const KeyframeData& keyframe, const geometry::SE3& T_w_b_keyframe,
              const Prediction& prediction) const override;

 private:
  AlignmentResult align(const vision::EdgePyramid& pyr, const KeyframeData& keyframe, const geometry::SE3& T_nr_init,
                        const Prediction& prediction, PredictionCheck* check) const;
  KeyframeReason keyframeVote(const vision::EdgePyramid& pyr, const KeyframeData& keyframe, const AlignmentResult& a) const;

  const camera::StereoRectifier& rect_;
  vision::VisionOptions vision_;
  AlignmentOptions alignment_;
  TrackingOptions tracking_;
  geometry::SE3 T_b_c_;  ///< body → rectified left camera
};

}  // namespace edgevio::tracking
