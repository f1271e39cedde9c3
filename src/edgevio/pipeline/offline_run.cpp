#include "edgevio/pipeline/offline_run.h"

#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <atomic>
#include <exception>
#include <memory>
#include <thread>

#include "edgevio/camera/stereo_rectifier.h"
#include "edgevio/common/error.h"
#include "edgevio/common/json.h"
#include "edgevio/imu/gyro_integration.h"
#include "edgevio/io/euroc_dataset.h"
#include "edgevio/io/trajectory_io.h"
#include "edgevio/pipeline/bounded_queue.h"
#include "edgevio/pipeline/odometry.h"

namespace edgevio::pipeline {

namespace fs = std::filesystem;

RunSummary runOffline(const RunRequest& req, const Config& config, const RunProgress& progress, const EventLog& event_log) {
  const auto wall_start = std::chrono::steady_clock::now();
  if (const std::string bad_mode = checkMode(req.mode); !bad_mode.empty()) throw InputError(bad_mode);
  if (req.skip < 0) throw InputError("--skip must be >= 0");
  const std::string invalid = config.validate();
  if (!invalid.empty()) throw InputError("invalid configuration: " + invalid);

  io::EurocDataset dataset(req.dataset, config.dataset);
  const camera::StereoRectifier rect(dataset.calibration(), config.rectification);
  const auto& pairs = dataset.stereoPairs();
  if (pairs.empty()) throw InputError(req.dataset, 0, "no stereo pairs to process");

  std::error_code ec;
  fs::create_directories(req.out_dir, ec);
  std::ofstream frames_csv(fs::path(req.out_dir) / "frames.csv");
  if (!frames_csv) throw InputError(req.out_dir, 0, "cannot write to the output folder");
  frames_csv << "timestamp_ns,keyframe,keyframe_reason,aligned,self_check,reference_points,points_used,visible_ratio,"
                "iterations,mean_distance_px,translation_sigma_m,reference_timestamp_ns,link_tx,link_ty,link_tz,link_qx,link_qy,link_qz,link_qw,"
                "prediction_check,external_check,external_rotation_deg,external_translation_m,"
                "est_iterations,est_initial_cost,est_final_cost,marginalized,back_links,loop_candidates,loop_accepted,loop_window_rejected,canny_ms,dt_ms,lines_ms,bm_ms,align_ms,back_link_ms,"
                "solve_ms,marginalize_ms,loop_ms,total_ms\n";
  {
    std::ofstream cfg(fs::path(req.out_dir) / "config.yaml");
    writeConfig(cfg, config);
  }

  // Static start: gravity-aligned initial orientation and gyro bias (METHOD.md §5).
  const imu::StaticInit init =
      imu::staticInitialization(dataset.imu(), pairs.front().t_ns, config.tracking.static_init_window_s,
                                config.tracking.static_accel_std_max, config.tracking.static_gyro_std_max);

  const geometry::SE3 T_b_c = rect.T_b_rect(0);
  Odometry odometry(req.mode, config, dataset.calibration(), rect, dataset.imu(), init, req.realtime);
  RunSummary s;
  // Written as the run goes: memory does not grow with the sequence's length.
  io::TrajectoryWriter tum((fs::path(req.out_dir) / "trajectory_tum.txt").string(), io::TrajectoryFormat::kTum);
  io::TrajectoryWriter euroc((fs::path(req.out_dir) / "trajectory.csv").string(), io::TrajectoryFormat::kEuroc,
                             isImuMode(req.mode));
  const std::size_t step = static_cast<std::size_t>(req.skip) + 1;
  const std::size_t total = (pairs.size() + step - 1) / step;

  // Three threads (METHOD.md §1): the driver reads and rectifies, the second
  // builds edge pyramids, this one tracks and estimates. Offline, the queues
  // block and every frame is processed in order: the result does not depend
  // on thread timing. In real time the driver releases frames at their
  // timestamps and drops those the pipeline has no room for.
  struct Loaded {
    std::int64_t t_ns = 0;
    bool readable = false;
    tracking::StereoFrame frame;
    double driver_ms = 0.0;
  };
  struct Prepared {
    std::int64_t t_ns = 0;
    bool readable = false;
    tracking::PreparedFrame frame;
    double driver_ms = 0.0, prepare_ms = 0.0;
  };
  BoundedQueue<Loaded> loaded(2);
  BoundedQueue<Prepared> prepared(2);
  std::exception_ptr driver_error, prepare_error;
  std::atomic<std::size_t> dropped{0};
  const auto msSince = [](std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
  };
  std::thread driver([&] {
    try {
      const auto start = std::chrono::steady_clock::now();
      for (std::size_t i = 0; i < pairs.size(); i += step) {
        if (req.realtime)
          std::this_thread::sleep_until(start + std::chrono::nanoseconds(pairs[i].t_ns - pairs.front().t_ns));
        const auto f0 = std::chrono::steady_clock::now();
        Loaded item;
        item.t_ns = pairs[i].t_ns;
        if (std::optional<cv::Mat> left = dataset.loadImage(i, 0)) {
          item.readable = true;
          item.frame.t_ns = pairs[i].t_ns;
          item.frame.left = rect.rectify(0, *left);
          // Decoded by the tracking thread if the frame becomes a keyframe.
          item.frame.right = tracking::LazyImage([&rect, path = pairs[i].right.path] {
            const cv::Mat raw = io::decodeGrayImage(path);
            const camera::CameraModel& m = rect.rawCamera(1);
            return raw.cols == m.width && raw.rows == m.height ? rect.rectify(1, raw) : cv::Mat();
          });
        }
        item.driver_ms = msSince(f0);
        if (!req.realtime)
          loaded.push(std::move(item));
        else if (!loaded.tryPush(std::move(item)))
          ++dropped;
      }
    } catch (...) {
      driver_error = std::current_exception();
    }
    loaded.close();
  });
  std::thread preparer([&] {
    try {
      while (std::optional<Loaded> item = loaded.pop()) {
        const auto f0 = std::chrono::steady_clock::now();
        Prepared p;
        p.t_ns = item->t_ns;
        p.readable = item->readable;
        p.driver_ms = item->driver_ms;
        if (item->readable) p.frame = tracking::prepareFrame(item->frame, rect, config.vision);
        p.prepare_ms = msSince(f0);
        prepared.push(std::move(p));
      }
    } catch (...) {
      prepare_error = std::current_exception();
      loaded.close();
    }
    prepared.close();
  });
  // Whatever happens below, the threads are stopped and joined.
  struct Joiner {
    std::function<void()> stop;
    ~Joiner() { stop(); }
  } joiner{[&] {
    loaded.close();
    prepared.close();
    if (driver.joinable()) driver.join();
    if (preparer.joinable()) preparer.join();
  }};

  std::size_t done = 0;
  while (true) {
    std::optional<Prepared> item = prepared.pop();
    if (!item) break;
    ++done;
    if (!item->readable) {
      ++s.skipped_unreadable;
      continue;
    }
    const auto f0 = std::chrono::steady_clock::now();
    const FrameResult fr = odometry.process(std::move(item->frame));
    const tracking::FrameTrack& t = fr.track;
    const double total_ms = item->driver_ms + item->prepare_ms + msSince(f0);

    io::TrajectorySample sample;
    sample.t_ns = t.t_ns;
    sample.T_w_b = fr.T_w_b;
    if (fr.state) {
      sample.v_w = fr.state->v_w;
      sample.b_g = fr.state->b_g;
      sample.b_a = fr.state->b_a;
    }
    tum.write(sample);
    euroc.write(sample);
    ++s.frames;
    s.keyframes += t.keyframe + t.promoted_previous + fr.forced_keyframe;
    s.self_check_failures += t.aligned && !t.self_check_passed;
    s.gyro_check_realignments += t.gyro_check_failed;
    s.translation_check_realignments += t.translation_check_failed;
    s.external_check_rejections += fr.external_check == "rejected";
    for (const std::string& event :
         {fr.event, std::string(t.right_image_unreadable ? "right image unreadable: keyframe without depth" : "")}) {
      if (event.empty()) continue;
      char at[64];
      std::snprintf(at, sizeof at, "t = %.3f s: ", static_cast<double>(t.t_ns - pairs.front().t_ns) * 1e-9);
      s.events.push_back(at + event);
      if (event_log) event_log(s.events.back());
    }
    if (odometry.lost() && !s.failed) {
      s.failed = true;
      s.failure = "lost track: " + std::to_string(config.tracking.lost_after_failures) +
                  " consecutive self-check failures ending at t = " + std::to_string(static_cast<double>(t.t_ns) * 1e-9) + " s";
    }
    if (!fr.T_w_b.translation().allFinite() && !s.failed) {
      s.failed = true;
      s.failure = "diverged: non-finite pose";
    }
    const estimator::EstimatorUpdate& e = fr.estimator;
    // The alignment's T_nr as the body's motion T_bn_br (what ground truth
    // gives directly: T_w_bn⁻¹·T_w_br), so the front end can be judged alone.
    const geometry::SE3 link = T_b_c * t.alignment.T_nr * T_b_c.inverse();
    const Quat& q = link.quaternion();
    char row[1024];
    std::snprintf(row, sizeof row,
                  "%lld,%d,%s,%d,%d,%d,%d,%.4f,%d,%.4f,%.4g,%lld,%.6f,%.6f,%.6f,%.9f,%.9f,%.9f,%.9f,%s,%s,%.3f,%.4f,%d,%.6g,%.6g,%s,%d,%d,%d,%d,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f\n",
                  static_cast<long long>(t.t_ns), t.keyframe || fr.forced_keyframe ? 1 : 0,
                  t.keyframe_reason.empty() ? (t.promoted_previous ? "previous frame promoted"
                                               : fr.forced_keyframe ? "forced by the estimator" : "-")
                                            : t.keyframe_reason.c_str(),
                  t.aligned ? 1 : 0, t.self_check_passed ? 1 : 0, t.reference_points, t.alignment.points_used,
                  t.alignment.visible_ratio, t.alignment.iterations, t.alignment.mean_distance_px,
                  t.alignment.translation_sigma_m, static_cast<long long>(t.reference_t_ns), link.translation().x(),
                  link.translation().y(), link.translation().z(), q.x(), q.y(), q.z(), q.w(),
                  t.gyro_check_failed ? "gyro" : t.translation_check_failed ? "translation" : "-",
                  fr.external_check.c_str(), fr.external.rotation_deg, fr.external.translation_m, e.iterations,
                  e.initial_cost, e.final_cost, e.marginalized.c_str(), fr.back_links_added, fr.loop.candidates,
                  fr.loop.accepted - fr.loop.window_rejections, fr.loop.window_rejections, t.canny_ms,
                  t.dt_ms - t.lines_ms, t.lines_ms, t.bm_ms, t.alignment.ms, fr.back.ms, e.solve_ms, e.marginalize_ms,
                  fr.loop_ran ? fr.loop.ms : 0.0, total_ms);
    frames_csv << row;
    if (progress) progress(done + dropped, total, static_cast<double>(t.t_ns - pairs.front().t_ns) * 1e-9);
  }
  joiner.stop();
  if (driver_error) std::rethrow_exception(driver_error);
  if (prepare_error) std::rethrow_exception(prepare_error);
  s.dropped_frames = dropped;
  s.skipped_unreadable += dataset.unreadableImages(0) + dataset.unreadableImages(1) - s.skipped_unreadable;
  if (tum.count() == 0) throw InputError(req.dataset, 0, "no stereo pair could be read");

  s.estimator_resets = odometry.resets();
  s.loop_closures = odometry.loopClosures();
  s.back_links = odometry.backLinks();
  s.duration_s = static_cast<double>(pairs.back().t_ns - pairs.front().t_ns) * 1e-9;
  s.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  s.realtime_factor = s.wall_s > 0 ? s.duration_s / s.wall_s : 0.0;
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) == 0) s.peak_rss_mb = static_cast<double>(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB

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
  j.key("gyro_check_realignments").value(s.gyro_check_realignments);
  j.key("translation_check_realignments").value(s.translation_check_realignments);
  j.key("external_check_rejections").value(s.external_check_rejections);
  j.key("estimator_resets").value(odometry.resets());
  j.key("loop_closures").value(odometry.loopClosures());
  j.key("back_links").value(odometry.backLinks());
  j.key("skipped_unreadable_frames").value(s.skipped_unreadable);
  j.key("realtime").value(req.realtime);
  j.key("dropped_frames").value(s.dropped_frames);
  j.key("static_initialization").value(init.is_static);
  j.key("failed").value(s.failed);
  j.key("failure").value(s.failure);
  j.key("duration_s").value(s.duration_s);
  j.key("wall_s").value(s.wall_s);
  j.key("realtime_factor").value(s.realtime_factor);
  j.key("peak_rss_mb").value(s.peak_rss_mb);
  j.key("events").beginArray();
  for (const auto& ev : s.events) j.value(ev);
  j.endArray();
  j.key("warnings").beginArray();
  for (const auto& w : dataset.warnings()) j.value(w);
  j.endArray();
  j.endObject();
  return s;
}

}  // namespace edgevio::pipeline
