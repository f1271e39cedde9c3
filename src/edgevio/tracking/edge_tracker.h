#pragma once
// Edge-only visual odometry (METHOD.md §3): every frame is aligned to the
// current keyframe; the self check and the keyframe policy decide when a
// frame becomes the new keyframe (with its own stereo depth). The estimate is
// causal: the pose of a frame is known when the frame has been processed.
#include <opencv2/core.hpp>

#include <functional>
#include <memory>
#include <optional>
#include <string>

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
/// reference points with stereo depth. Immutable once made, shared with loop
/// closure while the keyframe is in the window.
struct KeyframeData {
  std::int64_t t_ns = 0;
  vision::EdgePyramid pyramid;
  vision::KeyframeDepth depth;
};

/// What happened to one frame.
struct FrameTrack {
  std::int64_t t_ns = 0;
  geometry::SE3 T_w_b;            ///< causal estimate of the body pose
  bool keyframe = false;
  bool aligned = false;           ///< an alignment was attempted (not for the first frame)
  bool self_check_passed = false;
  bool gyro_check_failed = false; ///< the first alignment disagreed with the gyroscope (re-aligned)
  bool translation_check_failed = false; ///< the first alignment's translation was far from the IMU prediction (re-aligned)
  bool promoted_previous = false; ///< alignment to the keyframe failed; the previous frame became a keyframe
  bool right_image_unreadable = false;  ///< a new keyframe's right image did not decode: it has no depth
  std::string keyframe_reason;    ///< why it became a keyframe
  AlignmentResult alignment;
  int reference_points = 0;       ///< level-0 reference points of the keyframe it was aligned to
  std::int64_t reference_t_ns = -1;  ///< timestamp of that keyframe (the tracking link's reference)
  double canny_ms = 0, dt_ms = 0, lines_ms = 0, bm_ms = 0;  ///< dt_ms includes lines_ms
};

/// What of a pose prediction the tracker's checks may trust: nothing (a first
/// frame, no IMU), its rotation (gyroscope: the gyro check), or all of it (the
/// IMU's prediction from the window's newest state: the translation check too).
enum class PredictionReliability { kNone, kRotation, kPose };

class EdgeTracker {
 public:
  /// The gyroscope's body rotation from a time [ns] to the frame being tracked.
  using GyroSince = std::function<std::optional<geometry::SO3>(std::int64_t)>;

  EdgeTracker(const camera::StereoRectifier& rectifier, const vision::VisionOptions& vision,
              const AlignmentOptions& alignment, const TrackingOptions& tracking);

  /// The first frame starts at T_w_b_init and becomes the first keyframe.
  /// `R_prev_cur` is the body rotation since the previous frame (from the
  /// gyroscope) when available.
  FrameTrack track(PreparedFrame frame, const std::optional<geometry::SO3>& R_prev_cur,
                   const geometry::SE3& T_w_b_init = geometry::SE3());

  /// The same with a full-pose prediction (the IMU's, METHOD.md §5): the
  /// initial guess of the alignment, the pose of a first frame, and the
  /// frame's pose when the alignment fails. `reliable` says which checks
  /// against the prediction apply.
  /// `gyro_since(t_ref)`: the body rotation R_bref_bcur from time t_ref to this
  /// frame by the gyroscope alone (empty: none); the alignment's rotation prior.
  FrameTrack track(PreparedFrame frame, const geometry::SE3& T_w_b_pred, PredictionReliability reliable,
                   const GyroSince& gyro_since = {});

  /// Replaces the poses of the keyframe and of the last frame with better
  /// estimates (the window's), looked up by timestamp.
  void correctPoses(const std::function<std::optional<geometry::SE3>(std::int64_t)>& pose_of);
  /// Makes the last tracked frame the keyframe (the estimator rejected its
  /// link, or the old keyframe left the window). False when it already is.
  bool promoteLastFrame();
  std::optional<std::int64_t> keyframeTime() const;
  /// The current keyframe's data (null before the first frame).
  std::shared_ptr<const KeyframeData> keyframeData() const;

  int consecutiveFailures() const { return consecutive_failures_; }
  bool lost() const { return consecutive_failures_ >= tracking_.lost_after_failures; }

 private:
  struct Keyframe {
    std::shared_ptr<const KeyframeData> data;
    geometry::SE3 T_w_c;
  };
  void makeKeyframe(vision::EdgePyramid pyramid, const LazyImage& right_full, const geometry::SE3& T_w_c, std::int64_t t_ns,
                    FrameTrack* out);
  /// Aligns `pyr` to the current keyframe from `T_w_b_pred`, with the gyro and
  /// translation checks; sets the flags of the checks that failed in `checks`.
  AlignmentResult alignToKeyframe(const vision::EdgePyramid& pyr, const geometry::SE3& T_w_b_pred,
                                  PredictionReliability reliable, const GyroSince& gyro_since, FrameTrack* checks) const;
  /// The previous frame, kept so that it can become a keyframe when the current
  /// frame fails to align to the old one (its pose is already known).
  struct Previous {
    vision::EdgePyramid pyramid;
    LazyImage right;
    geometry::SE3 T_w_b;
    std::int64_t t_ns = 0;
  };
  std::optional<Previous> previous_;

  const camera::StereoRectifier& rect_;
  vision::VisionOptions vision_;
  AlignmentOptions alignment_;
  TrackingOptions tracking_;
  geometry::SE3 T_b_c_;  // body → rectified left camera
  std::optional<Keyframe> keyframe_;
  geometry::SE3 T_w_b_prev_, T_w_b_prev2_;
  int consecutive_failures_ = 0;
  std::int64_t last_t_ns_ = -1;
};

}  // namespace edgevio::tracking
