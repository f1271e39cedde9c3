#include "edgevio/estimator/vio_estimator.h"

#include <chrono>
#include <cmath>

#include "edgevio/imu/preintegration.h"

namespace edgevio::estimator {

using geometry::SE3;

namespace {
double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

std::string EstimatorOptions::validate() const {
  if (window_size < 3) return "window_size: at least 3";
  if (max_iterations < 1) return "max_iterations: at least 1";
  if (!(huber_translation_m > 0 && huber_rotation_deg > 0)) return "huber_*: must be > 0";
  if (!(damping > 0)) return "damping: must be > 0";
  if (!(external_check_rotation_deg > 0 && external_check_translation_m > 0)) return "external_check_*: must be > 0";
  if (!(loop_check_rotation_deg > 0 && loop_check_translation_m > 0)) return "loop_check_*: must be > 0";
  if (!(front_translation_m > 0 && front_rotation_deg > 0)) return "front_*: must be > 0";
  if (!(visual_covariance_scale > 0)) return "visual_covariance_scale: must be > 0";
  if (!(imu_noise_inflation > 0)) return "imu_noise_inflation: must be > 0";
  if (!(gyro_bias_walk_inflation > 0 && accel_bias_walk_inflation > 0)) return "*_bias_walk_inflation: must be > 0";
  if (!(max_imu_gap_s > 0)) return "max_imu_gap_s: must be > 0";
  if (!(repropagate_accel_bias > 0 && repropagate_gyro_bias > 0)) return "repropagate_*: must be > 0";
  if (!(init_velocity_sigma > 0 && init_accel_bias_sigma > 0 && init_gyro_bias_sigma > 0 && init_tilt_sigma_deg > 0))
    return "init_*_sigma: must be > 0";
  if (!(reset_accel_bias > 0 && reset_gyro_bias > 0 && reset_velocity > 0)) return "reset_*: must be > 0";
  return {};
}

VioEstimator::VioEstimator(const EstimatorOptions& options, const camera::ImuNoise& noise, const SE3& T_b_c, bool inertial)
    : options_(options), noise_(noise), inertial_(inertial) {
  noise_.accel_noise_density *= options.imu_noise_inflation;
  noise_.gyro_noise_density *= options.imu_noise_inflation;
  noise_.accel_random_walk *= options.accel_bias_walk_inflation;
  noise_.gyro_random_walk *= options.gyro_bias_walk_inflation;
  window_.T_b_c = T_b_c;
}

SolverOptions VioEstimator::solverOptions() const {
  SolverOptions o = options_.solver();
  o.gauge_full_rotation = !inertial_;
  return o;
}

void VioEstimator::initialize(std::int64_t t_ns, const imu::NavState& x, bool velocity_known, bool attitude_known) {
  window_ = Window{{}, {}, {}, {}, window_.T_b_c};
  window_.states.push_back({t_ns, x, false});
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
  const double sg = velocity_known ? options_.init_gyro_bias_sigma : 10.0 * options_.init_gyro_bias_sigma;
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

std::optional<imu::Preintegration> VioEstimator::preintegrateTo(const std::vector<io::ImuSample>& imu, std::int64_t t_ns) const {
  const imu::NavState& x = newest();
  return imu::preintegrate(imu, newestTime(), t_ns, x.b_a, x.b_g, noise_, options_.max_imu_gap_s);
}

void VioEstimator::addState(std::int64_t t_ns, imu::Preintegration pre, const std::optional<SE3>& T_w_b) {
  const std::size_t i = window_.states.size() - 1;
  predicted_newest_ = predictState(window_.states[i].x, pre);
  imu::NavState x = predicted_newest_;
  if (T_w_b) {
    x.R_w_b = T_w_b->so3();
    x.p_w = T_w_b->translation();
  }
  window_.states.push_back({t_ns, x, false});
  window_.inertial.push_back({i, i + 1, std::move(pre)});
}

void VioEstimator::addStateWithoutImu(std::int64_t t_ns, const SE3& T_w_b) {
  imu::NavState x;
  x.R_w_b = T_w_b.so3();
  x.p_w = T_w_b.translation();
  predicted_newest_ = x;
  window_.states.push_back({t_ns, x, false});
}

bool VioEstimator::addVisualLink(std::size_t r, std::size_t n, const SE3& T_nr, const Mat6& covariance) {
  RelativePoseLink link;
  link.T_nr = T_nr;
  const Mat6 P = options_.visual_covariance_scale * covariance;
  link.information = P.ldlt().solve(Mat6::Identity());
  link.information = 0.5 * (link.information + link.information.transpose());
  if (!link.information.allFinite()) return false;
  window_.visual.push_back({r, n, link});
  return true;
}

bool VioEstimator::addLoopLink(std::int64_t t_ref_ns, std::int64_t t_new_ns, const SE3& T_nr, const Mat6& covariance) {
  const auto r = indexOf(t_ref_ns), n = indexOf(t_new_ns);
  if (!r || !n || *r == *n) return false;
  if (inertial_ && !externalCheck(T_nr, window_.states[*r].x, window_.states[*n].x, window_.T_b_c,
                                  options_.loop_check_rotation_deg, options_.loop_check_translation_m)
                       .accepted)
    return false;
  return addVisualLink(*r, *n, T_nr, covariance);
}

std::optional<ExternalCheckResult> VioEstimator::offerTrackingLink(std::int64_t t_ref_ns, const SE3& T_nr,
                                                                   const Mat6& covariance) {
  const auto r = indexOf(t_ref_ns);
  if (!r || *r + 1 == window_.states.size()) return std::nullopt;
  ExternalCheckResult check;
  if (inertial_)
    check = externalCheck(T_nr, window_.states[*r].x, predicted_newest_, window_.T_b_c, options_.external_check_rotation_deg,
                          options_.external_check_translation_m);
  if (check.accepted) addVisualLink(*r, window_.states.size() - 1, T_nr, covariance);
  return check;
}

void VioEstimator::markKeyframe(std::int64_t t_ns) {
  if (const auto i = indexOf(t_ns)) window_.states[*i].keyframe = true;
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

EstimatorUpdate VioEstimator::optimize(bool alignment_good, std::optional<std::int64_t> keyframe_t_ns) {
  EstimatorUpdate u;
  const auto t0 = std::chrono::steady_clock::now();
  // Re-integrate the links whose bias linearisation point is far from the
  // estimate (METHOD.md §4); first-order correction covers the rest.
  for (InertialLink& l : window_.inertial) {
    const imu::NavState& xi = window_.states[l.i].x;
    if ((xi.b_a - l.pre.linearizationBa()).norm() > options_.repropagate_accel_bias ||
        (xi.b_g - l.pre.linearizationBg()).norm() > options_.repropagate_gyro_bias)
      l.repropagate(xi.b_a, xi.b_g);
  }
  const SolveSummary s = solve(&window_, solverOptions());
  u.iterations = s.iterations;
  u.initial_cost = s.initial_cost;
  u.final_cost = s.final_cost;
  u.solve_ms = msSince(t0);
  u.reset_reason = checkHealth();
  if (!u.reset_reason.empty() || !std::isfinite(s.final_cost)) {
    if (u.reset_reason.empty()) u.reset_reason = "non-finite cost";
    return u;
  }
  if (window_.states.size() <= static_cast<std::size_t>(options_.window_size)) return u;

  const auto t1 = std::chrono::steady_clock::now();
  const std::size_t second = window_.states.size() - 2;
  bool front = false;
  const auto kf = keyframe_t_ns ? indexOf(*keyframe_t_ns) : std::nullopt;
  if (alignment_good && kf && !window_.states[second].keyframe) {
    const imu::NavState& a = window_.states[second].x;
    const imu::NavState& b = window_.states[*kf].x;
    const double dp = (a.p_w - b.p_w).norm();
    const double angle = geometry::angle(a.R_w_b.inverse() * b.R_w_b);
    front = dp / options_.front_translation_m + angle / (options_.front_rotation_deg * kDegToRad) < 1.0;
  }
  const std::size_t victim = front ? second : 0;
  u.keyframe_left_window = kf && *kf == victim;
  marginalize(&window_, victim, solverOptions());
  u.marginalized = front ? "front" : "back";
  u.marginalize_ms = msSince(t1);
  return u;
}

}  // namespace edgevio::estimator
