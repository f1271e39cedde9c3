#include "edgevio/estimator/vio_estimator.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "edgevio/imu/preintegration.h"

namespace edgevio::estimator {

using geometry::SE3;

namespace {
// Without a static start the gyroscope bias is only loosely known: its prior
// is this many times wider than after one (a MEMS gyroscope's turn-on bias
// spans ~0.01-0.1 rad/s; the static start measures it to ~1e-3).
constexpr double kUnknownGyroBiasFactor = 10.0;

double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

VioEstimator::VioEstimator(const EstimatorOptions& options, const imu::ImuNoise& noise, const SE3& T_b_c, bool inertial,
                           const Vec3& start_gyro_bias)
    : options_(options), noise_(noise), inertial_(inertial), start_gyro_bias_(start_gyro_bias) {
  noise_.accel_noise_density *= options.imu_noise_inflation;
  noise_.gyro_noise_density *= options.imu_noise_inflation;
  noise_.accel_random_walk *= options.accel_bias_walk_inflation;
  noise_.gyro_random_walk *= options.gyro_bias_walk_inflation;
  window_.T_b_c = T_b_c;
  window_.gauge = inertial ? Gauge::kPositionYaw : Gauge::kPose;
  if (inertial && (options.estimate_time_offset || options.estimate_cam_imu_rotation || options.estimate_cam_imu_translation)) {
    CalibrationState c;
    c.time_offset = options.estimate_time_offset;
    c.rotation = options.estimate_cam_imu_rotation;
    c.translation = options.estimate_cam_imu_translation;
    c.time_offset_sigma_s = options.time_offset_sigma_ms * 1e-3;
    c.rotation_sigma_rad = options.cam_imu_rotation_sigma_deg * kDegToRad;
    c.translation_sigma_m = options.cam_imu_translation_sigma_m;
    window_.calibration = c;
  }
}

void VioEstimator::initialize(std::int64_t t_ns, const imu::NavState& x, bool velocity_known, bool attitude_known) {
  // The calibration's estimate outlives a restart; what the marginalised states said of it does not.
  window_ = Window{{}, {}, {}, {}, window_.T_b_c, window_.gauge, window_.calibration};
  window_.states.push_back({t_ns, x, timeOffset(), Vec3::Zero(), {}});
  predicted_newest_ = x;
  // Initial prior (METHOD.md §5 initialisation): position and yaw are the
  // gauge and stay free. Roll and pitch, when known (from the mean
  // accelerometer reading up to accel bias / g, or carried across a gap),
  // get init_tilt_sigma_deg: tilt is otherwise nearly unobservable over the
  // first frames (½gΔt² is 1 cm over 50 ms). A known velocity and gyro bias
  // get their init_* sigmas; otherwise the velocity is free and the gyro bias
  // loosely known.
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(15, 15);
  const double sv = options_.init_velocity_sigma, sa = options_.init_accel_bias_sigma;
  const double sg = velocity_known ? options_.init_gyro_bias_sigma : kUnknownGyroBiasFactor * options_.init_gyro_bias_sigma;
  if (velocity_known) H.block<3, 3>(imu::kV, imu::kV) = Mat3::Identity() / (sv * sv);
  if (attitude_known) {
    // Tilt: the world x and y components of the rotation error R·δθ.
    const double st = options_.init_tilt_sigma_deg * kDegToRad;
    const Mat3 R = x.R_w_b.matrix();
    H.block<3, 3>(imu::kR, imu::kR) = R.transpose() * Vec3(1, 1, 0).asDiagonal() * R / (st * st);
  }
  H.block<3, 3>(imu::kBa, imu::kBa) = Mat3::Identity() / (sa * sa);
  H.block<3, 3>(imu::kBg, imu::kBg) = Mat3::Identity() / (sg * sg);
  window_.prior.states = {0};
  window_.prior.x0 = {x};
  window_.prior.H = H;
  window_.prior.b = Eigen::VectorXd::Zero(15);
}

void VioEstimator::restartAfterGap(std::int64_t t_ns, const SE3& T_w_b, const Vec3& v_w, bool attitude_known) {
  imu::NavState x = newest();
  x.R_w_b = T_w_b.so3();
  x.p_w = T_w_b.translation();
  x.v_w = v_w;
  initialize(t_ns, x, false, attitude_known);
}

void VioEstimator::restartAfterBlowUp(const SE3& pose) {
  // Keep what is still plausible; an implausible velocity or bias starts
  // again from zero (the gyroscope's from the static start's).
  imu::NavState x = newest();
  x.R_w_b = pose.so3();
  x.p_w = pose.translation();
  if (!x.v_w.allFinite() || x.v_w.norm() > options_.reset_velocity) x.v_w.setZero();
  if (!x.b_a.allFinite() || x.b_a.norm() > options_.reset_accel_bias) x.b_a.setZero();
  if (!x.b_g.allFinite() || x.b_g.norm() > options_.reset_gyro_bias) x.b_g = start_gyro_bias_;
  initialize(newestTime(), x, false, false);
}

std::optional<std::size_t> VioEstimator::indexOf(std::int64_t t_ns) const {
  for (std::size_t i = window_.states.size(); i-- > 0;)
    if (window_.states[i].t_ns == t_ns) return i;
  return std::nullopt;
}

std::optional<imu::NavState> VioEstimator::stateAt(std::int64_t t_ns) const {
  const auto i = indexOf(t_ns);
  if (!i) return std::nullopt;
  return window_.states[*i].x;
}

std::optional<imu::Preintegration> VioEstimator::preintegrateTo(const std::vector<imu::ImuSample>& imu, std::int64_t t_ns) const {
  const WindowState& s = window_.states.back();
  const std::int64_t t0 = s.t_ns + toNanoseconds(s.time_offset_s);
  return imu::preintegrate(imu, t0, imuTime(t_ns), s.x.b_a, s.x.b_g, noise_, options_.max_imu_gap_s);
}

bool VioEstimator::imuCovers(const std::vector<imu::ImuSample>& imu, std::int64_t t0_ns, std::int64_t t1_ns) const {
  const imu::NavState& x = newest();
  return imu::preintegrate(imu, imuTime(t0_ns), imuTime(t1_ns), x.b_a, x.b_g, noise_, options_.max_imu_gap_s).has_value();
}

void VioEstimator::addState(std::int64_t t_ns, imu::Preintegration pre) {
  const std::size_t i = window_.states.size() - 1;
  predicted_newest_ = imu::predictState(window_.states[i].x, pre);
  window_.states.push_back(
      {t_ns, predicted_newest_, timeOffset(), pre.lastGyro(), {}});
  window_.inertial.push_back({i, i + 1, std::move(pre)});
}

void VioEstimator::addStateWithoutImu(std::int64_t t_ns, const SE3& T_w_b) {
  imu::NavState x;
  x.R_w_b = T_w_b.so3();
  x.p_w = T_w_b.translation();
  predicted_newest_ = x;
  window_.states.push_back({t_ns, x, 0.0, Vec3::Zero(), {}});
}

bool VioEstimator::addVisualLink(std::size_t r, std::size_t n, const SE3& T_nr, const Mat6& covariance,
                                 std::shared_ptr<const vision::EdgePyramid> image) {
  RelativePoseLink link;
  link.T_nr = T_nr;
  const Mat6 P = options_.visual_covariance_scale * covariance;
  link.information = P.ldlt().solve(Mat6::Identity());
  link.information = 0.5 * (link.information + link.information.transpose());
  if (!link.information.allFinite()) return false;
  window_.visual.push_back({r, n, link, options_.coupling == Coupling::kTight ? std::move(image) : nullptr});
  return true;
}

bool VioEstimator::setKeyframePoints(std::int64_t t_ns, KeyframePoints points) {
  const auto i = indexOf(t_ns);
  if (!i) return false;
  window_.states[*i].points = std::move(points);
  return true;
}

bool VioEstimator::addLoopLink(std::int64_t t_ref_ns, std::int64_t t_new_ns, const SE3& T_nr, const Mat6& covariance) {
  const auto r = indexOf(t_ref_ns), n = indexOf(t_new_ns);
  if (!r || !n || *r == *n) return false;
  if (inertial_ && !externalCheck(T_nr, window_.states[*r].x, window_.states[*n].x, cameraExtrinsics(),
                                  options_.loop_check_rotation_deg, options_.loop_check_translation_m)
                       .accepted)
    return false;
  return addVisualLink(*r, *n, T_nr, covariance);
}

std::optional<ExternalCheckResult> VioEstimator::offerTrackingLink(std::int64_t t_ref_ns, const SE3& T_nr,
                                                                   const Mat6& covariance,
                                                                   std::shared_ptr<const vision::EdgePyramid> image) {
  const auto r = indexOf(t_ref_ns);
  if (!r || *r + 1 == window_.states.size()) return std::nullopt;
  ExternalCheckResult check;
  if (inertial_)
    check = externalCheck(T_nr, window_.states[*r].x, predicted_newest_, cameraExtrinsics(), options_.external_check_rotation_deg,
                          options_.external_check_translation_m);
  if (!check.accepted) return check;
  const bool tight = image && !window_.states[*r].points.empty() && options_.coupling == Coupling::kTight;
  if (addVisualLink(*r, window_.states.size() - 1, T_nr, covariance, std::move(image)) && tight) {
    // Edge residuals converge only near their minimum: the newest state
    // starts where the alignment put its camera, not at the IMU's prediction.
    const SE3 T_b_c = cameraExtrinsics();
    const imu::NavState& xr = window_.states[*r].x;
    const SE3 T_w_bn = SE3(xr.R_w_b, xr.p_w) * T_b_c * T_nr.inverse() * T_b_c.inverse();
    window_.states.back().x.R_w_b = T_w_bn.so3();
    window_.states.back().x.p_w = T_w_bn.translation();
  }
  return check;
}

std::string VioEstimator::checkHealth() const {
  for (const WindowState& s : window_.states) {
    const imu::NavState& x = s.x;
    if (!x.p_w.allFinite() || !x.v_w.allFinite() || !x.R_w_b.matrix().allFinite() || !x.b_a.allFinite() || !x.b_g.allFinite())
      return "non-finite state";
    if (x.b_a.norm() > options_.reset_accel_bias) return "accelerometer bias beyond reset_accel_bias";
    if (x.b_g.norm() > options_.reset_gyro_bias) return "gyro bias beyond reset_gyro_bias";
    if (x.v_w.norm() > options_.reset_velocity) return "speed beyond reset_velocity";
  }
  return {};
}

std::size_t VioEstimator::marginalizationVictim(bool alignment_good, const KeyframeQuery& keyframes) const {
  const std::size_t second = window_.states.size() - 2;
  const auto kf = keyframes.current ? indexOf(*keyframes.current) : std::nullopt;
  if (!alignment_good || !kf || keyframes.is_keyframe(window_.states[second].t_ns)) return 0;
  const imu::NavState& a = window_.states[second].x;
  const imu::NavState& b = window_.states[*kf].x;
  const double dp = (a.p_w - b.p_w).norm();
  const double angle = geometry::angle(a.R_w_b.inverse() * b.R_w_b);
  return dp / options_.front_translation_m + angle / (options_.front_rotation_deg * kDegToRad) < 1.0 ? second : 0;
}

EstimatorUpdate VioEstimator::optimize(bool alignment_good, const KeyframeQuery& keyframes, const SE3& restart_pose) {
  EstimatorUpdate u = solveWindow(restart_pose, options_.max_iterations);
  if (u.reset_reason.empty()) marginalizeWhenFull(alignment_good, keyframes, &u);
  return u;
}

EstimatorUpdate VioEstimator::solveWindow(const SE3& restart_pose, int iterations) {
  // Re-integrate the links whose bias linearisation point is far from the
  // estimate (METHOD.md §4); first-order correction covers the rest.
  const auto t0 = std::chrono::steady_clock::now();
  for (InertialLink& l : window_.inertial) {
    const imu::NavState& xi = window_.states[l.i].x;
    if ((xi.b_a - l.pre.linearizationBa()).norm() > options_.repropagate_accel_bias ||
        (xi.b_g - l.pre.linearizationBg()).norm() > options_.repropagate_gyro_bias)
      l.repropagate(xi.b_a, xi.b_g);
  }
  EstimatorUpdate u;
  u.solve_ms = msSince(t0);
  iterations_left_ = options_.max_iterations;
  iterate(std::min(iterations, options_.max_iterations), restart_pose, &u);
  return u;
}

void VioEstimator::finishSolve(const SE3& restart_pose, EstimatorUpdate* u) {
  if (iterations_left_ > 0) iterate(iterations_left_, restart_pose, u);
}

void VioEstimator::iterate(int iterations, const SE3& restart_pose, EstimatorUpdate* u) {
  const auto t0 = std::chrono::steady_clock::now();
  EstimatorOptions o = options_;
  o.max_iterations = iterations;
  // 0: the newest state alone, a pose before the window's iterations, which all follow.
  const SolveSummary s = iterations == 0 ? solveNewest(&window_, options_) : solve(&window_, o);
  if (iterations > 0) {
    if (iterations_left_ == options_.max_iterations) u->initial_cost = s.initial_cost;
    // A step that vanished or failed ends the frame's solve, as it would have in one call.
    iterations_left_ = s.stopped ? 0 : iterations_left_ - iterations;
    u->iterations += s.iterations;
    u->final_cost = s.final_cost;
  }
  u->reset_reason = checkHealth();
  if (u->reset_reason.empty() && !std::isfinite(s.final_cost)) u->reset_reason = "non-finite cost";
  if (!u->reset_reason.empty()) {
    restartAfterBlowUp(restart_pose);
    iterations_left_ = 0;
  }
  u->solve_ms += msSince(t0);
}

void VioEstimator::marginalizeWhenFull(bool alignment_good, const KeyframeQuery& keyframes, EstimatorUpdate* u) {
  if (window_.states.size() <= static_cast<std::size_t>(options_.window_size)) return;
  const auto t1 = std::chrono::steady_clock::now();
  const std::size_t victim = marginalizationVictim(alignment_good, keyframes);
  u->marginalized = victim == 0 ? Marginalization::kBack : Marginalization::kFront;
  u->marginalized_t_ns = window_.states[victim].t_ns;
  marginalize(&window_, victim, options_);
  u->marginalize_ms = msSince(t1);
}

}  // namespace edgevio::estimator
