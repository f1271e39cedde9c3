// How consistent the window's inputs are with their covariances (issue 31,
// point 1), on renders whose truth is known:
//  - the tracking links that entered the window: their error against the
//    ground truth, e = Log(T_nr,true⁻¹·T_nr) (the alignment's right
//    perturbation), normalised by the alignment's covariance (JᵀWJ)⁻¹: the
//    NEES eᵀΣ⁻¹e has mean 6 for a consistent 6-dof estimate;
//  - how much of a link's error its keyframe shares with the other links to
//    it: per component, the intraclass correlation of the normalised errors
//    grouped by keyframe (between-keyframe variance over total), and the
//    correlation of consecutive links to one keyframe;
//  - the IMU preintegration between consecutive frames: the residual of eq 17
//    at the true states (velocity and biases from the ground truth) against
//    its covariance at the calibration's densities: mean 9 over the motion
//    block if consistent;
//  - where the links' error comes from (a second table): the NEES by the
//    time from the keyframe, of the difference of consecutive links to one
//    keyframe, and the part of the translation error that is a scale error.
//  - with --true-depth, all of it (and the run's ATE) with every keyframe's
//    reference points moved along their rays to the render's true depth:
//    what the links and the trajectory would be if stereo depth were exact,
//    and how far the stereo depth is off (a last table); with
//    --true-depth-on-surfaces, points on occlusion boundaries (where the
//    true depth of an edge is ambiguous) keep their stereo depth.
// Usage: link_consistency_bench [--mode edge+imu] [--skip K] [--imu-truth FILE] [--true-depth | --true-depth-on-surfaces] DATASET...
// (renders with ground truth; --imu-truth: a ground truth with velocity and
// bias columns for the IMU part, e.g. EuRoC's groundtruth.csv beside a render
// that replays its IMU log; --true-depth: renders of `edgevio simulate`, whose
// simulation.yaml brings back the scene). Prints one markdown row per dataset
// and a total, then the second table.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <unistd.h>

#include "edgevio/camera/stereo_rectifier.h"
#include "edgevio/config/config.h"
#include "edgevio/sim/simulation_record.h"
#include "edgevio/eval/metrics.h"
#include "edgevio/imu/preintegration.h"
#include "edgevio/io/sequence.h"
#include "edgevio/io/trajectory_io.h"
#include "edgevio/pipeline/mode.h"
#include "edgevio/pipeline/run.h"
#include "edgevio/sim/renderer.h"
#include "edgevio/sim/simulator.h"
#include "edgevio/tracking/edge_tracker.h"

using namespace edgevio;
using geometry::SE3;

namespace {

struct Link {
  std::int64_t t_ns, t_ref_ns;
  Vec6 normalised;  ///< e_k/σ_k per component: unit variance when consistent
  double nees;      ///< eᵀΣ⁻¹e
  Vec6 e;
  Mat6 covariance;       ///< the alignment's (JᵀWJ)⁻¹
  Vec3 t_true, t_error;  ///< the true translation of T_nr and the measured one's error
  double mean_distance_px = 0.0;  ///< the alignment's mean distance of its points to the nearest edge
};

/// Sums over the datasets.
struct Totals {
  std::size_t links = 0, inertial = 0;
  double nees = 0, inertial_nees = 0;
  Vec6 sum_sq = Vec6::Zero();
};

/// How far the keyframes' stereo depth was from the truth, on level 0:
/// (ρ − ρ_true)/ρ_true per reference point.
struct DepthErrors {
  std::vector<double> relative;
  std::vector<double> depth_m;  ///< the true depth of each
  std::size_t points = 0, silhouettes = 0;  ///< points the render saw, and those on an occlusion boundary
};

/// Where the true depth replaces stereo's: everywhere (on an occlusion
/// boundary, the nearer side's), or on surfaces only (a boundary's points
/// keep their stereo depth).
enum class TrueDepth { kOff, kEverywhere, kSurfacesOnly };
constexpr float kSilhouetteRatio = 1.05f;

/// The edge tracker with each keyframe's reference points moved along their
/// rays to the render's true depth: the nearest surface within a pixel of
/// the point's projection at the camera's full resolution (an edge on an
/// occlusion boundary is the nearer side's). Runs on the tracking thread only.
class TrueDepthTracker final : public tracking::Tracker {
 public:
  TrueDepthTracker(const camera::StereoRectifier& rect, const Config& config, const sim::SimulatedWorld& world,
                   TrueDepth mode, DepthErrors* errors)
      : mode_(mode),
        inner_(rect, config.vision, config.alignment, config.tracking),
        rect_(rect),
        world_(world),
        rays_(rect.rectifiedCamera()),
        errors_(errors) {}

  std::shared_ptr<const tracking::KeyframeData> makeKeyframe(tracking::PreparedFrame frame) const override {
    const std::int64_t t = frame.t_ns;
    auto k = std::make_shared<tracking::KeyframeData>(*inner_.makeKeyframe(std::move(frame)));
    cv::Mat radiance, z;
    sim::RenderOptions ro;
    ro.threads = 1;
    sim::render(world_.scene, rays_, world_.motion.pose(t) * rect_.T_b_rect(0), ro, &radiance, &z);
    const camera::CameraModel& cam = rect_.rectifiedCamera();
    for (std::size_t level = 0; level < k->depth.points.size(); ++level) {
      for (Eigen::Vector3f& P : k->depth.points[level]) {
        const Vec2 uv = cam.project(P.cast<double>());
        const int u = static_cast<int>(std::lround(uv.x())), v = static_cast<int>(std::lround(uv.y()));
        float nearest = std::numeric_limits<float>::infinity(), farthest = 0.0f;
        for (int dv = -1; dv <= 1; ++dv)
          for (int du = -1; du <= 1; ++du)
            if (u + du >= 0 && v + dv >= 0 && u + du < z.cols && v + dv < z.rows) {
              nearest = std::min(nearest, z.at<float>(v + dv, u + du));
              farthest = std::max(farthest, z.at<float>(v + dv, u + du));
            }
        if (!std::isfinite(nearest) || nearest <= 0) continue;  // the render saw nothing there: keep the stereo depth
        // Depths more than 5 % apart within the pixel: an occlusion boundary, where "the" true depth is ambiguous.
        const bool silhouette = farthest > kSilhouetteRatio * nearest;
        if (level == 0) {
          ++errors_->points;
          errors_->silhouettes += silhouette;
        }
        if (silhouette && mode_ == TrueDepth::kSurfacesOnly) continue;
        if (level == 0) {
          errors_->relative.push_back(static_cast<double>(nearest / P.z()) - 1.0);  // ρ/ρ_true − 1
          errors_->depth_m.push_back(nearest);
        }
        P *= nearest / P.z();
      }
    }
    return k;
  }
  tracking::Track track(const tracking::PreparedFrame& frame, const tracking::KeyframeData& keyframe,
                        const SE3& T_w_b_keyframe, const tracking::Prediction& prediction) const override {
    return inner_.track(frame, keyframe, T_w_b_keyframe, prediction);
  }

 private:
  TrueDepth mode_;
  tracking::EdgeTracker inner_;
  const camera::StereoRectifier& rect_;
  const sim::SimulatedWorld& world_;
  sim::RayTable rays_;
  DepthErrors* errors_;
};

/// The ground truth at t (linear interpolation of position, velocity and
/// biases, slerp of rotation between the bracketing samples); false outside.
bool truthAt(const io::Trajectory& gt, std::int64_t t, io::TrajectorySample* out) {
  const auto it = std::lower_bound(gt.begin(), gt.end(), t, [](const io::TrajectorySample& s, std::int64_t v) { return s.t_ns < v; });
  if (it == gt.end() || (it == gt.begin() && it->t_ns != t)) return false;
  if (it->t_ns == t) {
    *out = *it;
    return true;
  }
  const io::TrajectorySample &a = *(it - 1), &b = *it;
  const double f = static_cast<double>(t - a.t_ns) / static_cast<double>(b.t_ns - a.t_ns);
  out->t_ns = t;
  out->T_w_b = geometry::interpolate(a.T_w_b, b.T_w_b, f);
  out->v_w = a.v_w + f * (b.v_w - a.v_w);
  out->b_g = a.b_g + f * (b.b_g - a.b_g);
  out->b_a = a.b_a + f * (b.b_a - a.b_a);
  return true;
}

imu::NavState navState(const io::TrajectorySample& s) {
  imu::NavState x;
  x.R_w_b = s.T_w_b.so3();
  x.p_w = s.T_w_b.translation();
  x.v_w = s.v_w;
  x.b_a = s.b_a;
  x.b_g = s.b_g;
  return x;
}

/// Intraclass correlation of component k over groups: the share of the
/// variance that the group (the keyframe) explains, by one-way ANOVA,
/// (MSB − MSW)/(MSB + (n̄−1)MSW).
double intraclassCorrelation(const std::map<std::int64_t, std::vector<const Link*>>& groups, int k) {
  double grand = 0;
  std::size_t n = 0, g = 0;
  for (const auto& [t, links] : groups) {
    if (links.size() < 2) continue;
    for (const Link* l : links) grand += l->normalised[k];
    n += links.size();
    ++g;
  }
  if (g < 2 || n <= g) return std::nan("");
  grand /= static_cast<double>(n);
  double ssb = 0, ssw = 0;
  for (const auto& [t, links] : groups) {
    if (links.size() < 2) continue;
    double mean = 0;
    for (const Link* l : links) mean += l->normalised[k];
    mean /= static_cast<double>(links.size());
    ssb += static_cast<double>(links.size()) * (mean - grand) * (mean - grand);
    for (const Link* l : links) ssw += (l->normalised[k] - mean) * (l->normalised[k] - mean);
  }
  const double msb = ssb / static_cast<double>(g - 1), msw = ssw / static_cast<double>(n - g);
  const double n_bar = static_cast<double>(n) / static_cast<double>(g);
  return (msb - msw) / (msb + (n_bar - 1) * msw);
}

double median(std::vector<double> v) {
  if (v.empty()) return std::nan("");
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

/// Correlation of component k between consecutive links to the same keyframe.
double consecutiveCorrelation(const std::vector<Link>& links, int k) {
  double sxy = 0, sxx = 0, syy = 0;
  for (std::size_t i = 1; i < links.size(); ++i) {
    if (links[i].t_ref_ns != links[i - 1].t_ref_ns) continue;
    const double x = links[i - 1].normalised[k], y = links[i].normalised[k];
    sxy += x * y;
    sxx += x * x;
    syy += y * y;
  }
  return sxx > 0 && syy > 0 ? sxy / std::sqrt(sxx * syy) : std::nan("");
}

/// Correlation of component k between the mean errors of consecutive
/// keyframes' links (keyframes with two links or more), uncentred: an error
/// that every keyframe hands on to the next, a bias among them, counts.
double nextKeyframeCorrelation(const std::map<std::int64_t, std::vector<const Link*>>& groups, int k) {
  double sxy = 0, sxx = 0, syy = 0, previous = std::nan("");
  for (const auto& [t, links] : groups) {
    if (links.size() < 2) {
      previous = std::nan("");
      continue;
    }
    double mean = 0;
    for (const Link* l : links) mean += l->normalised[k];
    mean /= static_cast<double>(links.size());
    if (!std::isnan(previous)) {
      sxy += previous * mean;
      sxx += previous * previous;
      syy += mean * mean;
    }
    previous = mean;
  }
  return sxx > 0 && syy > 0 ? sxy / std::sqrt(sxx * syy) : std::nan("");
}

/// Where the links' error comes from, as one markdown row: the NEES by the
/// time from the keyframe; the NEES of the difference of consecutive links
/// to one keyframe against Σ_n + Σ_m (6 if their errors are independent,
/// 6(1 − ρ) if they share ρ of them); and the translation error along the
/// true translation read as a scale error δ = (Δt·t)/|t|² (a keyframe's depth
/// error would scale all its links' translations alike): the share of the
/// squared translation error it explains (1/3 for an error of no preferred
/// direction) and the intraclass correlation of δ by keyframe; the
/// correlation of consecutive keyframes' mean errors (translation, rotation).
std::string sharedPartRow(const std::string& name, const std::vector<Link>& links,
                          const std::map<std::int64_t, std::vector<const Link*>>& by_keyframe) {
  std::string row = "| " + name + " |";
  const double bins[] = {0.0, 0.1, 0.2, 0.4, 1e9};
  for (int b = 0; b < 4; ++b) {
    double sum = 0;
    std::size_t count = 0;
    for (const Link& l : links) {
      const double gap_s = static_cast<double>(l.t_ns - l.t_ref_ns) * 1e-9;
      if (gap_s < bins[b] || gap_s >= bins[b + 1]) continue;
      sum += l.nees;
      ++count;
    }
    char cell[64];
    std::snprintf(cell, sizeof(cell), " %.1f (%zu) |", count ? sum / static_cast<double>(count) : std::nan(""), count);
    row += cell;
  }
  double difference_nees = 0;
  std::size_t differences = 0;
  for (std::size_t i = 1; i < links.size(); ++i) {
    if (links[i].t_ref_ns != links[i - 1].t_ref_ns) continue;
    const Vec6 d = links[i].e - links[i - 1].e;
    difference_nees += d.dot((links[i].covariance + links[i - 1].covariance).ldlt().solve(d));
    ++differences;
  }
  double along = 0, all = 0;
  std::vector<Link> scales;  // `normalised` holds δ in every component
  for (const Link& l : links) {
    all += l.t_error.squaredNorm();
    if (l.t_true.norm() < 0.05) continue;  // too short a translation to have a scale
    const double delta = l.t_error.dot(l.t_true) / l.t_true.squaredNorm();
    along += (delta * l.t_true).squaredNorm();
    scales.push_back(l);
    scales.back().normalised = Vec6::Constant(delta);
  }
  std::map<std::int64_t, std::vector<const Link*>> scale_by_keyframe;
  for (const Link& l : scales) scale_by_keyframe[l.t_ref_ns].push_back(&l);
  const auto next = [&](int first) {
    return (nextKeyframeCorrelation(by_keyframe, first) + nextKeyframeCorrelation(by_keyframe, first + 1) +
            nextKeyframeCorrelation(by_keyframe, first + 2)) / 3;
  };
  char tail[160];
  std::snprintf(tail, sizeof(tail), " %.2f (%zu) | %.2f | %.2f | %.2f %.2f |",
                differences ? difference_nees / static_cast<double>(differences) : std::nan(""), differences,
                all > 0 ? along / all : std::nan(""), intraclassCorrelation(scale_by_keyframe, 0), next(0), next(3));
  return row + tail;
}

/// One markdown row of the keyframes' stereo depth error against the truth:
/// median and RMS of (ρ − ρ_true)/ρ_true, its mean (a bias common to all), the
/// share beyond 10 %, and the median by true depth.
std::string depthErrorRow(const std::string& name, const DepthErrors& d) {
  std::vector<double> abs_err;
  double sum = 0, sum_sq = 0;
  std::size_t beyond = 0;
  for (double e : d.relative) {
    abs_err.push_back(std::abs(e));
    sum += e;
    sum_sq += e * e;
    beyond += std::abs(e) > 0.1;
  }
  const double n = static_cast<double>(std::max<std::size_t>(d.relative.size(), 1));
  std::string row = "| " + name + " | " + std::to_string(d.relative.size()) + " |";
  char cell[160];
  std::snprintf(cell, sizeof(cell), " %.3f | %.4f | %.4f | %+.4f | %.3f |",
                static_cast<double>(d.silhouettes) / static_cast<double>(std::max<std::size_t>(d.points, 1)),
                median(abs_err), std::sqrt(sum_sq / n), sum / n, static_cast<double>(beyond) / n);
  row += cell;
  const double bins[] = {0.0, 2.0, 4.0, 8.0, 1e9};
  for (int b = 0; b < 4; ++b) {
    std::vector<double> in_bin;
    for (std::size_t i = 0; i < d.relative.size(); ++i)
      if (d.depth_m[i] >= bins[b] && d.depth_m[i] < bins[b + 1]) in_bin.push_back(std::abs(d.relative[i]));
    std::snprintf(cell, sizeof(cell), " %.4f (%zu) |", median(in_bin), in_bin.size());
    row += cell;
  }
  return row;
}

/// One markdown row: the NEES divided by the square of the alignment's mean
/// point distance ῡ [px], overall and by the time from the keyframe; the
/// same spread over the time bins and renders as the NEES itself would mean
/// that ῡ²·(JᵀWJ)⁻¹ is a covariance whose scale fits every link.
std::string residualScaledRow(const std::string& name, const std::vector<Link>& links) {
  std::string row = "| " + name + " |";
  const double bins[] = {0.0, 1e9, 0.0, 0.1, 0.2, 0.4, 1e9};
  char cell[64];
  for (int b = 0; b < 5; ++b) {
    const double lo = b == 0 ? bins[0] : bins[b + 1], hi = b == 0 ? bins[1] : bins[b + 2];
    double sum = 0, distance = 0;
    std::size_t count = 0;
    for (const Link& l : links) {
      const double gap_s = static_cast<double>(l.t_ns - l.t_ref_ns) * 1e-9;
      if (gap_s < lo || gap_s >= hi || !(l.mean_distance_px > 0)) continue;
      sum += l.nees / (l.mean_distance_px * l.mean_distance_px);
      distance += l.mean_distance_px;
      ++count;
    }
    const double n = static_cast<double>(std::max<std::size_t>(count, 1));
    std::snprintf(cell, sizeof(cell), " %.1f (%.2f px) |", count ? sum / n : std::nan(""), distance / n);
    row += cell;
  }
  return row;
}

void analyse(const std::string& dataset, pipeline::Mode mode, int skip, const std::string& imu_truth, TrueDepth true_depth,
             Totals* totals, std::string* shared_part_row, std::string* residual_row, std::string* depth_row) {
  // The folder's name, with or without a trailing slash.
  const std::string name = std::filesystem::path(dataset + "/").lexically_normal().parent_path().filename().string();
  const io::Trajectory gt = io::readTrajectory(dataset + "/mav0/state_groundtruth_estimate0/data.csv");
  const io::Trajectory imu_gt = imu_truth.empty() ? gt : io::readTrajectory(imu_truth);
  const Config config;
  SE3 T_b_c;
  std::vector<imu::ImuSample> imu;
  imu::ImuNoise noise;
  std::vector<Link> links;
  pipeline::RunObserver observer;
  observer.opened = [&](const io::Sequence& s) {
    T_b_c = camera::StereoRectifier(s.calibration(), config.rectification).T_b_rect(0);
    imu = s.imu();
    noise = s.calibration().imu;
  };
  std::vector<std::int64_t> frame_times;
  observer.frame = [&](const pipeline::FrameRecord& r, const std::vector<std::uint8_t>&) {
    frame_times.push_back(r.t_ns);
    if (r.external_check != pipeline::ExternalCheck::kAccepted || r.reference_t_ns < 0) return;
    io::TrajectorySample n, ref;
    if (!truthAt(gt, r.t_ns, &n) || !truthAt(gt, r.reference_t_ns, &ref)) return;
    const SE3 truth = (n.T_w_b * T_b_c).inverse() * (ref.T_w_b * T_b_c);
    const Vec6 e = (truth.inverse() * r.alignment.T_nr).log();
    const Eigen::LLT<Mat6> llt(r.alignment.covariance);
    if (llt.info() != Eigen::Success) return;
    const Vec6 sigma = r.alignment.covariance.diagonal().cwiseSqrt();
    Link l{r.t_ns, r.reference_t_ns, e.cwiseQuotient(sigma), llt.matrixL().solve(e).squaredNorm(), e, r.alignment.covariance, truth.translation(),
           r.alignment.T_nr.translation() - truth.translation()};
    l.mean_distance_px = r.alignment.mean_distance_px;
    links.push_back(l);
  };
  // One folder per process: several benches may run side by side.
  const std::string out =
      (std::filesystem::temp_directory_path() / ("edgevio_link_consistency." + std::to_string(getpid()))).string();
  pipeline::RunRequest req(dataset, out, mode, skip);
  req.picture_stride = 0;
  std::optional<sim::SimulatedWorld> world;
  DepthErrors depth_errors;
  if (true_depth != TrueDepth::kOff) {
    const sim::SimulationRecord record = sim::loadSimulationRecord(dataset);
    world = sim::simulatedWorld(record.request, record.options);
    req.tracker = [&](const camera::StereoRectifier& rect, const Config& c) -> std::unique_ptr<tracking::Tracker> {
      return std::make_unique<TrueDepthTracker>(rect, c, *world, true_depth, &depth_errors);
    };
  }
  pipeline::run(req, config, observer);
  const double ate_m = eval::evaluate(gt, io::readTrajectory(out + "/trajectory_tum.txt"), config.eval).ate_rmse_m;
  std::filesystem::remove_all(out);
  if (true_depth != TrueDepth::kOff) *depth_row = depthErrorRow(name, depth_errors);

  // The IMU between consecutive frames at the true states.
  double inertial_nees = 0;
  std::size_t inertial = 0;
  std::vector<double> inertial_each;
  for (std::size_t i = 1; i < frame_times.size(); ++i) {
    io::TrajectorySample a, b;
    if (!truthAt(imu_gt, frame_times[i - 1], &a) || !truthAt(imu_gt, frame_times[i], &b) || !a.hasVelocityAndBias()) continue;
    const auto pre = imu::preintegrate(imu, a.t_ns, b.t_ns, a.b_a, a.b_g, noise, config.estimator.max_imu_gap_s);
    if (!pre) continue;
    const imu::Vec15 r = pre->residual(navState(a), navState(b));
    const Eigen::Matrix<double, 9, 9> P = pre->covariance().topLeftCorner<9, 9>();
    inertial_each.push_back(r.head<9>().dot(P.ldlt().solve(r.head<9>())));
    inertial_nees += inertial_each.back();
    ++inertial;
  }

  double nees = 0;
  Vec6 sum_sq = Vec6::Zero();
  std::map<std::int64_t, std::vector<const Link*>> by_keyframe;
  std::vector<double> link_each;
  for (const Link& l : links) {
    link_each.push_back(l.nees);
    nees += l.nees;
    sum_sq += l.normalised.cwiseAbs2();
    by_keyframe[l.t_ref_ns].push_back(&l);
  }
  const double m = static_cast<double>(std::max<std::size_t>(links.size(), 1));
  std::printf("| %s | %.4f | %zu | %.1f (%.1f) | %.2f %.2f %.2f | %.2f %.2f %.2f | %.2f %.2f | %.2f %.2f | %.2f (%.2f) |\n",
              name.c_str(), ate_m, links.size(), nees / m, median(link_each), std::sqrt(sum_sq[0] / m),
              std::sqrt(sum_sq[1] / m), std::sqrt(sum_sq[2] / m), std::sqrt(sum_sq[3] / m), std::sqrt(sum_sq[4] / m),
              std::sqrt(sum_sq[5] / m), (intraclassCorrelation(by_keyframe, 0) + intraclassCorrelation(by_keyframe, 1) +
                                        intraclassCorrelation(by_keyframe, 2)) / 3,
              (intraclassCorrelation(by_keyframe, 3) + intraclassCorrelation(by_keyframe, 4) +
               intraclassCorrelation(by_keyframe, 5)) / 3,
              (consecutiveCorrelation(links, 0) + consecutiveCorrelation(links, 1) + consecutiveCorrelation(links, 2)) / 3,
              (consecutiveCorrelation(links, 3) + consecutiveCorrelation(links, 4) + consecutiveCorrelation(links, 5)) / 3,
              inertial ? inertial_nees / static_cast<double>(inertial) : std::nan(""), median(inertial_each));
  *shared_part_row = sharedPartRow(name, links, by_keyframe);
  *residual_row = residualScaledRow(name, links);
  std::fflush(stdout);
  totals->links += links.size();
  totals->nees += nees;
  totals->sum_sq += sum_sq;
  totals->inertial += inertial;
  totals->inertial_nees += inertial_nees;
}

}  // namespace

int main(int argc, char** argv) {
  pipeline::Mode mode{true, false};
  std::vector<std::string> datasets;
  std::string imu_truth;
  int skip = 0;
  TrueDepth true_depth = TrueDepth::kOff;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--skip") == 0 && i + 1 < argc) {
      char* end = nullptr;
      const long k = std::strtol(argv[++i], &end, 10);
      if (end == argv[i] || *end != '\0' || k < 0 || k > 1000) {
        std::fprintf(stderr, "--skip: an integer from 0 to 1000, not '%s'\n", argv[i]);
        return 2;
      }
      skip = static_cast<int>(k);
      continue;
    }
    if (std::strcmp(argv[i], "--true-depth") == 0 || std::strcmp(argv[i], "--true-depth-on-surfaces") == 0) {
      true_depth = std::strcmp(argv[i], "--true-depth") == 0 ? TrueDepth::kEverywhere : TrueDepth::kSurfacesOnly;
      continue;
    }
    if (std::strcmp(argv[i], "--imu-truth") == 0 && i + 1 < argc) {
      imu_truth = argv[++i];
      continue;
    }
    if (std::strcmp(argv[i], "--mode") == 0 && i + 1 < argc) {
      const auto m = pipeline::parseMode(argv[++i]);
      if (!m) {
        std::fprintf(stderr, "--mode: one of %s\n", pipeline::kModeNames);
        return 2;
      }
      mode = *m;
    } else {
      datasets.emplace_back(argv[i]);
    }
  }
  if (datasets.empty()) {
    std::fprintf(stderr, "usage: %s [--mode edge+imu] [--skip K] [--imu-truth FILE] [--true-depth | --true-depth-on-surfaces] DATASET...\n", argv[0]);
    return 2;
  }
  std::printf("mode %s, skip %d%s; ATE RMSE (SE(3)); NEES against the alignment's covariance (JtWJ)^-1 (6 if consistent; the window uses it x "
              "estimator.visual_covariance_scale); RMS of e_k/sigma_k per component (1 if consistent); "
              "intraclass correlation by keyframe and correlation of consecutive links to one keyframe (0 if "
              "independent); IMU NEES of the motion block at the calibration's densities (9 if consistent). The median of a "
              "consistent NEES is 5.35 (6 dof) and 8.34 (9 dof)\n\n",
              pipeline::modeName(mode).c_str(), skip,
              true_depth == TrueDepth::kEverywhere       ? ", keyframes at the true depth"
              : true_depth == TrueDepth::kSurfacesOnly ? ", keyframes at the true depth off occlusion boundaries"
                                                       : "");
  std::printf("| dataset | ATE m | links | NEES mean (median) | RMS e/sigma: tx ty tz | rx ry rz | ICC t, r | consecutive t, r | IMU NEES mean (median) |\n");
  std::printf("|---|---:|---:|---:|---|---|---|---|---:|\n");
  Totals t;
  std::vector<std::string> shared_part_rows(datasets.size()), residual_rows(datasets.size()), depth_rows(datasets.size());
  for (std::size_t i = 0; i < datasets.size(); ++i)
    analyse(datasets[i], mode, skip, imu_truth, true_depth, &t, &shared_part_rows[i], &residual_rows[i], &depth_rows[i]);
  const double m = static_cast<double>(std::max<std::size_t>(t.links, 1));
  std::printf("| all | | %zu | %.1f | %.2f %.2f %.2f | %.2f %.2f %.2f | | | %.2f |\n", t.links, t.nees / m, std::sqrt(t.sum_sq[0] / m),
              std::sqrt(t.sum_sq[1] / m), std::sqrt(t.sum_sq[2] / m), std::sqrt(t.sum_sq[3] / m), std::sqrt(t.sum_sq[4] / m),
              std::sqrt(t.sum_sq[5] / m), t.inertial ? t.inertial_nees / static_cast<double>(t.inertial) : std::nan(""));
  std::printf("\nWhere the error comes from: NEES (links) by the time from the keyframe; NEES of the difference of consecutive "
              "links to one keyframe against the sum of their covariances (6 if independent); the translation error along the "
              "true translation as a scale error: its share of the squared error (1/3 if of no preferred direction) and its "
              "intraclass correlation by keyframe; the correlation of consecutive keyframes' mean normalised errors, "
              "uncentred (0 if each keyframe's error is its own)\n\n");
  std::printf("| dataset | < 0.1 s | 0.1-0.2 s | 0.2-0.4 s | >= 0.4 s | consecutive differences | scale share | scale ICC | "
              "next keyframe t, r |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---|\n");
  for (const std::string& row : shared_part_rows) std::printf("%s\n", row.c_str());
  std::printf("\nThe NEES over the square of the alignment's mean point distance (its mean), all links and by the time "
              "from the keyframe: as flat as the NEES over renders and times if that distance sets each link's scale\n\n");
  std::printf("| dataset | all | < 0.1 s | 0.1-0.2 s | 0.2-0.4 s | >= 0.4 s |\n|---|---:|---:|---:|---:|---:|\n");
  for (const std::string& row : residual_rows) std::printf("%s\n", row.c_str());
  if (true_depth == TrueDepth::kOff) return 0;
  std::printf("\nThe keyframes' stereo depth against the truth, level 0: the share of points on occlusion boundaries "
              "(depths within the pixel more than 5 %% apart); over the points compared, |rho - rho_true|/rho_true, median "
              "and RMS, its mean (signed), the share beyond 10 %%; the median by true depth (points)\n\n");
  std::printf("| dataset | points | boundary | median | RMS | mean | > 10 %% | < 2 m | 2-4 m | 4-8 m | >= 8 m |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const std::string& row : depth_rows) std::printf("%s\n", row.c_str());
  return 0;
}
