// `diagnose`: reads a sequence once, aligning each frame to its predecessor
// with the front end (no IMU), and hands the measurements to the checks.
#include "edgevio/doctor/doctor.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <memory>

#include "edgevio/camera/stereo_rectifier.h"
#include "edgevio/common/time.h"
#include "edgevio/config/config.h"
#include "edgevio/imu/gyro_integration.h"
#include "edgevio/io/sequence.h"
#include "edgevio/tracking/edge_tracker.h"

namespace edgevio::doctor {

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

namespace {


/// Frame timing from the stamps of every frame.
void checkTiming(const io::Sequence& seq, ImageCheck* c) {
  std::vector<double> spacing;
  for (std::size_t i = 1; i < seq.frameCount(); ++i) spacing.push_back(toSeconds(seq.frameTime(i) - seq.frameTime(i - 1)));
  const double period = median(spacing);
  if (!(period > 0)) return;
  c->rate_hz = 1.0 / period;
  for (double dt : spacing)
    if (dt > 1.5 * period) c->missing_frames += static_cast<int>(std::lround(dt / period)) - 1;
}

/// Mean grey level, edge sharpness, clipping.
void imageStatistics(const cv::Mat& raw, const vision::EdgeLevel& level0, const DoctorOptions& o, double t_s, ImageCheck* c) {
  c->t_s.push_back(t_s);
  c->brightness.push_back(cv::mean(raw)[0]);
  c->sharpness.push_back(edgeSharpness(level0.image, level0.edges));
  const double pixels = static_cast<double>(raw.total());
  if (cv::countNonZero(raw >= 255) > o.clipped_pixels * pixels) ++c->overexposed_frames;
  if (cv::countNonZero(raw <= 5) > o.clipped_pixels * pixels) ++c->underexposed_frames;
}

}  // namespace

double edgeSharpness(const cv::Mat& image, const cv::Mat& edges) {
  if (cv::countNonZero(edges) == 0) return 0.0;
  cv::Mat gx, gy, magnitude;
  cv::Sobel(image, gx, CV_32F, 1, 0, 3);
  cv::Sobel(image, gy, CV_32F, 0, 1, 3);
  cv::magnitude(gx, gy, magnitude);
  return cv::mean(magnitude, edges)[0] / 8.0;  // a 3x3 Sobel is 8x the grey step per pixel
}

std::vector<double> verticalDisparities(const cv::Mat& left, const cv::Mat& right, int max_disparity) {
  constexpr int kRows = 6, kHalf = 5;
  std::vector<cv::Point2f> corners;
  cv::goodFeaturesToTrack(left, corners, 300, 0.01, 12);
  std::vector<double> dy;
  for (const cv::Point2f& p : corners) {
    const int x = static_cast<int>(std::lround(p.x)), y = static_cast<int>(std::lround(p.y));
    const int x0 = x - max_disparity - kHalf, y0 = y - kRows - kHalf;
    if (x0 < 0 || y0 < 0 || x + kHalf >= left.cols || y + kRows + kHalf >= left.rows) continue;
    const cv::Mat patch = left(cv::Rect(x - kHalf, y - kHalf, 2 * kHalf + 1, 2 * kHalf + 1));
    const cv::Mat strip = right(cv::Rect(x0, y0, max_disparity + 2 * kHalf + 1, 2 * (kRows + kHalf) + 1));
    cv::Mat score;
    cv::matchTemplate(strip, patch, score, cv::TM_CCOEFF_NORMED);
    double best = 0;
    cv::Point at;
    cv::minMaxLoc(score, nullptr, &best, nullptr, &at);
    if (best < 0.9 || at.y == 0 || at.y == score.rows - 1) continue;
    cv::Mat others = score.clone();
    cv::rectangle(others, cv::Rect(at.x - 2, 0, 5, score.rows), cv::Scalar(-1), cv::FILLED);
    double second = 0;
    cv::minMaxLoc(others, nullptr, &second);
    if (second > best - 0.05) continue;
    const double up = score.at<float>(at.y - 1, at.x), mid = score.at<float>(at.y, at.x), down = score.at<float>(at.y + 1, at.x);
    const double curvature = up - 2 * mid + down;
    const double sub = curvature < 0 ? 0.5 * (up - down) / curvature : 0.0;
    dy.push_back(at.y + sub - kRows);
  }
  return dy;
}


DoctorReport diagnose(io::Sequence& seq, const Config& config, const DoctorProgress& progress) {
  const DoctorOptions& o = config.doctor;
  DoctorReport r;
  r.dataset = seq.location();
  r.imu = checkImu(seq.imu(), config.estimator.max_imu_gap_s, o);
  checkTiming(seq, &r.images);

  const camera::StereoRectifier rectifier(seq.calibration(), config.rectification);
  const tracking::EdgeTracker tracker(rectifier, config.vision, config.alignment, config.tracking);
  const geometry::SE3& T_b_c = rectifier.T_b_rect(0);
  std::size_t frames = 0;
  while (frames < seq.frameCount() && toSeconds(seq.frameTime(frames) - seq.frameTime(0)) <= o.max_duration_s) ++frames;
  const std::size_t stereo_every = std::max<std::size_t>(1, frames / static_cast<std::size_t>(o.stereo_frames));

  std::shared_ptr<const tracking::KeyframeData> previous;
  // The last frame-to-frame body motion as a twist per second: the next
  // alignment's prediction is this over the next interval (constant
  // velocity; a dropped frame doubles the interval).
  Vec6 twist_per_s = Vec6::Zero();
  std::vector<FrameRotation> rotations;
  double depth_points = 0, edge_pixels = 0;
  for (std::size_t i = 0; i < frames; ++i) {
    if (progress) progress(i, frames);
    const std::optional<cv::Mat> raw = seq.leftImage(i);
    if (!raw) {
      previous.reset();
      continue;
    }
    const std::function<cv::Mat()> right_raw = seq.rightImageLoader(i);
    tracking::StereoFrame frame{seq.frameTime(i), rectifier.rectify(0, *raw), tracking::LazyImage([&rectifier, right_raw] {
                                  const cv::Mat image = right_raw();
                                  return image.empty() ? image : rectifier.rectify(1, image);
                                })};
    tracking::PreparedFrame prepared = tracking::prepareFrame(frame, rectifier, config.vision);
    imageStatistics(*raw, prepared.pyramid.levels[0], o, toSeconds(frame.t_ns - seq.frameTime(0)), &r.images);
    ++r.images.frames;
    if (previous) {
      // The alignment starts from the gyroscope's rotation where it has one,
      // as in a run: from constant velocity alone, fast rotation across a
      // dropped frame led the alignments into wrong basins that passed
      // their self check, each the next one's prediction, for seconds. The
      // start point does not bias the result (the tests' known offsets and
      // rotations are found): the alignment converges to the images' own
      // optimum, and is not checked against the gyroscope.
      tracking::Prediction prediction;
      prediction.T_w_b = geometry::SE3::exp(twist_per_s * toSeconds(frame.t_ns - previous->t_ns));
      geometry::SO3 gyro_rotation;
      if (imu::integrateGyro(seq.imu(), previous->t_ns, frame.t_ns, Vec3::Zero(), config.estimator.max_imu_gap_s,
                             &gyro_rotation))
        prediction.T_w_b = geometry::SE3(gyro_rotation, prediction.T_w_b.translation());
      const tracking::Track track = tracker.track(prepared, *previous, geometry::SE3(), prediction);
      if (track.passed()) {
        twist_per_s = track.T_w_b.log() / toSeconds(frame.t_ns - previous->t_ns);
        rotations.push_back({previous->t_ns, frame.t_ns, (T_b_c.inverse() * track.T_w_b * T_b_c).so3()});
      } else {
        twist_per_s = Vec6::Zero();
        ++r.motion.failed_alignments;
      }
    }
    if (i % stereo_every == 0 && !prepared.right.get().empty()) {
      const std::vector<double> dy = verticalDisparities(prepared.pyramid.full, prepared.right.get(), config.vision.stereo_num_disparities);
      r.stereo.vertical_disparities.insert(r.stereo.vertical_disparities.end(), dy.begin(), dy.end());
      ++r.stereo.frames;
    }
    previous = tracker.makeKeyframe(std::move(prepared));
    edge_pixels += previous->pyramid.levels[0].edge_count;
    depth_points += previous->referencePoints();
    r.duration_s = toSeconds(frame.t_ns - seq.frameTime(0));
  }
  if (progress) progress(frames, frames);

  std::vector<double> change;
  for (std::size_t k = 1; k < r.images.brightness.size(); ++k) {
    const double before = std::max(1.0, r.images.brightness[k - 1]);
    if (std::abs(r.images.brightness[k] - before) > o.exposure_jump * before) ++r.images.exposure_changes;
  }
  const double sharp = median(r.images.sharpness);
  for (double s : r.images.sharpness) r.images.blurred_frames += s < o.blur_ratio * sharp;

  StereoCheck& st = r.stereo;
  st.matches = st.vertical_disparities.size();
  st.vertical_disparity_px = median(st.vertical_disparities);
  std::vector<double> magnitude;
  for (double d : st.vertical_disparities) magnitude.push_back(std::abs(d));
  st.abs_vertical_disparity_px = median(magnitude);
  st.valid_depth_fraction = edge_pixels > 0 ? depth_points / edge_pixels : 0.0;

  const std::size_t failed = r.motion.failed_alignments;
  r.motion = checkMotion(rotations, seq.imu(), T_b_c.so3(), config.estimator.max_imu_gap_s, o);
  r.motion.failed_alignments = failed;
  r.findings = findFindings(r, seq.calibration(), config.estimator.max_imu_gap_s, o);
  return r;
}

}  // namespace edgevio::doctor
