#include "edgevio/pipeline/offline_run.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>

#include "edgevio/camera/stereo_rectifier.h"
#include "edgevio/common/error.h"
#include "edgevio/common/json.h"
#include "edgevio/imu/gyro_integration.h"
#include "edgevio/io/euroc_dataset.h"
#include "edgevio/io/trajectory_io.h"
#include "edgevio/tracking/edge_tracker.h"

namespace edgevio::pipeline {

namespace fs = std::filesystem;

RunSummary runOffline(const RunRequest& req, const Config& config, const RunProgress& progress) {
  const auto wall_start = std::chrono::steady_clock::now();
  if (req.mode != "edge-only")
    throw InputError("mode '" + req.mode + "' is not implemented yet (edge-only is; edge+imu and the loop modes follow)");
  if (req.skip < 0) throw InputError("--skip must be >= 0");
  const std::string invalid = config.validate();
  if (!invalid.empty()) throw InputError("invalid configuration: " + invalid);

  io::EurocDataset dataset(req.dataset, config.dataset);
  const camera::StereoRectifier rect(dataset.calibration(), config.rectification);
  tracking::EdgeTracker tracker(rect, config.vision, config.alignment, config.tracking);
  const auto& pairs = dataset.stereoPairs();
  if (pairs.empty()) throw InputError(req.dataset, 0, "no stereo pairs to process");

  std::error_code ec;
  fs::create_directories(req.out_dir, ec);
  std::ofstream frames_csv(fs::path(req.out_dir) / "frames.csv");
  if (!frames_csv) throw InputError(req.out_dir, 0, "cannot write to the output folder");
  frames_csv << "timestamp_ns,keyframe,keyframe_reason,aligned,self_check,reference_points,points_used,visible_ratio,"
                "iterations,mean_distance_px,canny_ms,dt_ms,lines_ms,bm_ms,align_ms,total_ms\n";
  {
    std::ofstream cfg(fs::path(req.out_dir) / "config.yaml");
    writeConfig(cfg, config);
  }

  // Static start: gravity-aligned initial orientation and gyro bias (METHOD.md §5).
  const imu::StaticInit init =
      imu::staticInitialization(dataset.imu(), pairs.front().t_ns, config.tracking.static_init_window_s,
                                config.tracking.static_accel_std_max, config.tracking.static_gyro_std_max);

  RunSummary s;
  io::Trajectory trajectory;
  const std::size_t step = static_cast<std::size_t>(req.skip) + 1;
  const std::size_t total = (pairs.size() + step - 1) / step;
  std::int64_t t_prev = -1;
  std::size_t done = 0;
  for (std::size_t i = 0; i < pairs.size(); i += step) {
    const auto f0 = std::chrono::steady_clock::now();
    std::optional<io::StereoImages> images = dataset.loadStereo(i);
    ++done;
    if (!images) {
      ++s.skipped_unreadable;
      continue;
    }
    tracking::StereoFrame frame;
    frame.t_ns = images->t_ns;
    rect.rectify(images->left, images->right, &frame.left, &frame.right);
    std::optional<geometry::SO3> dR;
    if (t_prev >= 0) {
      geometry::SO3 R;
      if (imu::integrateGyro(dataset.imu(), t_prev, frame.t_ns, init.gyro_bias, &R)) dR = R;
    }
    const tracking::FrameTrack t = tracker.track(frame, dR, geometry::SE3(init.R_w_b, Vec3::Zero()));
    t_prev = frame.t_ns;
    const double total_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - f0).count();

    io::TrajectorySample sample;
    sample.t_ns = t.t_ns;
    sample.T_w_b = t.T_w_b;
    trajectory.push_back(sample);
    ++s.frames;
    s.keyframes += t.keyframe + t.promoted_previous;
    s.self_check_failures += t.aligned && !t.self_check_passed;
    if (tracker.lost() && !s.failed) {
      s.failed = true;
      s.failure = "lost track: " + std::to_string(config.tracking.lost_after_failures) +
                  " consecutive self-check failures ending at t = " + std::to_string(static_cast<double>(t.t_ns) * 1e-9) + " s";
    }
    if (!t.T_w_b.translation().allFinite() && !s.failed) {
      s.failed = true;
      s.failure = "diverged: non-finite pose";
    }
    char row[512];
    std::snprintf(row, sizeof row, "%lld,%d,%s,%d,%d,%d,%d,%.4f,%d,%.4f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f\n",
                  static_cast<long long>(t.t_ns), t.keyframe ? 1 : 0,
                  t.keyframe_reason.empty() ? (t.promoted_previous ? "previous frame promoted" : "-") : t.keyframe_reason.c_str(), t.aligned ? 1 : 0,
                  t.self_check_passed ? 1 : 0, t.reference_points, t.alignment.points_used, t.alignment.visible_ratio,
                  t.alignment.iterations, t.alignment.mean_distance_px, t.canny_ms, t.dt_ms - t.lines_ms, t.lines_ms, t.bm_ms,
                  t.alignment.ms, total_ms);
    frames_csv << row;
    if (progress) progress(done, total, static_cast<double>(t.t_ns - pairs.front().t_ns) * 1e-9);
  }
  s.skipped_unreadable += dataset.unreadableImages(0) + dataset.unreadableImages(1) - s.skipped_unreadable;
  if (trajectory.empty()) throw InputError(req.dataset, 0, "no stereo pair could be read");
  io::writeTrajectoryTum((fs::path(req.out_dir) / "trajectory_tum.txt").string(), trajectory);
  io::writeTrajectoryEuroc((fs::path(req.out_dir) / "trajectory.csv").string(), trajectory);

  s.duration_s = static_cast<double>(pairs.back().t_ns - pairs.front().t_ns) * 1e-9;
  s.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  s.realtime_factor = s.wall_s > 0 ? s.duration_s / s.wall_s : 0.0;

  std::ofstream js(fs::path(req.out_dir) / "summary.json");
  JsonWriter j(js);
  j.beginObject();
  j.key("mode").value(req.mode);
  j.key("sequence").value(fs::path(dataset.mav0()).parent_path().filename().string());
  j.key("dataset").value(fs::absolute(req.dataset).lexically_normal().string());
  j.key("skip").value(req.skip);
  j.key("frames").value(s.frames);
  j.key("keyframes").value(s.keyframes);
  j.key("self_check_failures").value(s.self_check_failures);
  j.key("external_check_rejections").value(0);
  j.key("loop_closures").value(0);
  j.key("skipped_unreadable_frames").value(s.skipped_unreadable);
  j.key("static_initialization").value(init.is_static);
  j.key("failed").value(s.failed);
  j.key("failure").value(s.failure);
  j.key("duration_s").value(s.duration_s);
  j.key("wall_s").value(s.wall_s);
  j.key("realtime_factor").value(s.realtime_factor);
  j.key("warnings").beginArray();
  for (const auto& w : dataset.warnings()) j.value(w);
  j.endArray();
  j.endObject();
  return s;
}

}  // namespace edgevio::pipeline
