#include "edgevio/sim/simulator.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "edgevio/common/error.h"
#include "edgevio/common/format.h"
#include "edgevio/common/time.h"
#include "edgevio/io/bag_sequence.h"
#include "edgevio/io/calibration_io.h"
#include "edgevio/io/imu_io.h"
#include "edgevio/io/png_writer.h"
#include "edgevio/io/trajectory_io.h"
#include "edgevio/sim/faults.h"
#include "edgevio/sim/imu_synth.h"
#include "edgevio/sim/random.h"
#include "edgevio/sim/renderer.h"
#include "edgevio/sim/sensor_model.h"
#include "edgevio/sim/trajectory_source.h"

namespace edgevio::sim {

namespace fs = std::filesystem;
using geometry::SE3;

namespace {

std::string seconds(std::int64_t t_ns) { return formatText("%.3f", toSeconds(t_ns)); }

/// Piecewise-constant light scale: sudden changes at random times.
class LightingChanges {
 public:
  LightingChanges(std::int64_t begin_ns, std::int64_t end_ns, double interval_s, double magnitude, std::uint64_t seed) {
    Rng rng(hashCombine(seed, 0x11947));
    double t = toSeconds(begin_ns);
    const double end = toSeconds(end_ns);
    while (true) {
      t += interval_s * rng.uniform(0.5, 1.5);
      if (t >= end) break;
      changes_.emplace_back(toNanoseconds(t), static_cast<float>(rng.uniform(1 - magnitude, 1 + magnitude)));
    }
  }
  float scale(std::int64_t t_ns) const {
    float s = 1.0f;
    for (const auto& [t, f] : changes_)
      if (t_ns >= t) s = f;
    return s;
  }

 private:
  std::vector<std::pair<std::int64_t, float>> changes_;
};

void writeSimulationYaml(const std::string& path, const SimRequest& r, const SimOptions& o) {
  std::ofstream f(path);
  f.precision(17);
  f << "# How this folder was made (edgevio simulate). Same request + seed = same bytes.\n"
    << "trajectory: \"" << r.trajectory_file << "\"\nscenario: \"" << r.scenario << "\"\nstart_s: " << r.start_s
    << "\nduration_s: " << r.duration_s << "\nseed: " << r.seed << "\nimu: \"" << r.imu << "\"\nnoise: "
    << (r.noise ? "true" : "false") << "\nblur_ms: " << r.blur_ms << "\nexposure_changes: "
    << (r.exposure_changes ? "true" : "false") << "\ndrop_rate: " << r.drop_rate << "\nskip: " << r.skip
    << "\ncalib: \"" << r.calib << "\"\nfaults: [";
  for (std::size_t i = 0; i < r.faults.size(); ++i) f << (i ? ", " : "") << "\"" << faultSpec(r.faults[i]) << "\"";
  f << "]\nsim:\n";
  for (const options::Field<SimOptions>& field : SimOptions::table().fields) f << "  " << field.key << ": " << field.format(o) << "\n";
}

/// sim.knot_dt_s, or the samples' median spacing where that is wider: denser
/// knots would only repeat the linear interpolation between samples. A
/// B-spline whose control points are samples of a motion p keeps
/// (4 + 2 cos 2πfΔ)/6 of its amplitude at frequency f (Δ: knot spacing), so
/// narrow knots matter for a replayed real IMU, which measured all of it.
double knotSpacing(const io::Trajectory& samples, double knot_dt_s) {
  if (samples.size() < 2) return knot_dt_s;
  std::vector<std::int64_t> gaps;
  gaps.reserve(samples.size() - 1);
  for (std::size_t i = 1; i < samples.size(); ++i) gaps.push_back(samples[i].t_ns - samples[i - 1].t_ns);
  std::nth_element(gaps.begin(), gaps.begin() + static_cast<std::ptrdiff_t>(gaps.size() / 2), gaps.end());
  return std::max(knot_dt_s, toSeconds(gaps[gaps.size() / 2]));
}

}  // namespace

SimulatedWorld simulatedWorld(const SimRequest& req, const SimOptions& options) {
  SimulatedWorld w;
  w.rig = req.calib.empty() ? io::eurocDefaultRig() : io::loadCalibration(req.calib);

  const double margin_s = 4 * options.knot_dt_s;  // spline support beyond the span
  if (!req.scenario.empty()) {
    const double duration = std::isnan(req.duration_s) ? options.scenario_duration_s : req.duration_s;
    if (!(duration > 0)) throw InputError("--duration must be > 0");
    w.samples = scenarioSamples(req.scenario, req.start_s + duration + margin_s, options.static_start_s, w.rig.T_b_c[0]);
    w.source = "scenario " + req.scenario;
    w.begin_ns = kScenarioStartNs + toNanoseconds(req.start_s);
    w.end_ns = w.begin_ns + toNanoseconds(duration);
  } else {
    w.samples = io::readTrajectory(req.trajectory_file);
    w.source = req.trajectory_file;
    w.position_steps_removed =
        removePositionSteps(w.samples, options.trajectory_max_accel_mps2, options.trajectory_step_spread_s);
    w.begin_ns = w.samples.front().t_ns + toNanoseconds(req.start_s);
    w.end_ns = std::isnan(req.duration_s) ? w.samples.back().t_ns : w.begin_ns + toNanoseconds(req.duration_s);
    if (w.begin_ns >= w.samples.back().t_ns || w.end_ns > w.samples.back().t_ns)
      throw InputError(w.source, 0, "the trajectory covers [" + seconds(w.samples.front().t_ns) + ", " +
                                        seconds(w.samples.back().t_ns) + "] s but [" + seconds(w.begin_ns) + ", " +
                                        seconds(w.end_ns) + "] s was requested (check --start and --duration)");
  }
  constexpr double kMinDuration = 0.5;
  if (toSeconds(w.end_ns - w.begin_ns) < kMinDuration)
    throw InputError(w.source, 0, "too short: the requested span is " + seconds(w.end_ns - w.begin_ns) +
                                      " s, at least " + std::to_string(kMinDuration) + " s are needed");
  w.knot_dt_s = knotSpacing(w.samples, options.knot_dt_s);
  w.motion = fitSpline(w.samples, w.begin_ns, w.end_ns, w.knot_dt_s, options.max_trajectory_gap_s, w.source);

  std::vector<Vec3> path;
  for (std::int64_t t = w.begin_ns; t <= w.end_ns; t += 20000000) path.push_back(w.motion.pose(t).translation());
  w.scene = buildScene(path, options.scene, req.seed);
  return w;
}

SimSummary simulate(const SimRequest& req, const SimOptions& options, const SimProgress& progress) {
  const auto wall_start = std::chrono::steady_clock::now();
  const std::string invalid = options::validate(options);
  if (!invalid.empty()) throw InputError("invalid sim option: " + invalid);
  if (req.out_dir.empty()) throw InputError("simulate needs --out DIR");
  if (req.trajectory_file.empty() == req.scenario.empty())
    throw InputError("simulate needs exactly one of --trajectory FILE or --scenario NAME");
  if (!(req.drop_rate >= 0.0 && req.drop_rate < 1.0)) throw InputError("--drop-rate must be in [0, 1)");
  if (req.skip < 0) throw InputError("--skip must be >= 0");
  if (!(req.blur_ms >= 0.0 && req.blur_ms < 200.0)) throw InputError("--blur-ms must be in [0, 200)");
  if (!(req.start_s >= 0.0)) throw InputError("--start must be >= 0");

  // 1-2. The motion and the world around it.
  const SimulatedWorld world = simulatedWorld(req, options);
  const camera::StereoRig& rig = world.rig;
  const io::Trajectory& samples = world.samples;
  const std::int64_t begin_ns = world.begin_ns, end_ns = world.end_ns;
  const SplineTrajectory& spline = world.motion;
  const Scene& scene = world.scene;

  // 3. The IMU.
  SynthesizedImu imu;
  if (req.imu == "synth") {
    ImuSynthOptions io_opts;
    io_opts.noise = req.noise;
    io_opts.densities = rig.imu;
    io_opts.initial_gyro_bias_sigma = options.initial_gyro_bias_sigma;
    io_opts.initial_accel_bias_sigma = options.initial_accel_bias_sigma;
    imu = synthesizeImu(spline, begin_ns, end_ns, io_opts, req.seed);
  } else {
    const std::vector<imu::ImuSample> all =
        io::RosbagReader::looksLikeBag(req.imu) ? io::readBagImu(req.imu) : io::readImuCsv(req.imu, 1e9, nullptr);
    if (all.empty()) throw InputError(req.imu, 0, "no IMU samples");
    for (const auto& s : all)
      if (s.t_ns >= begin_ns && s.t_ns <= end_ns) imu.samples.push_back(s);
    if (all.front().t_ns > begin_ns + 10000000 || all.back().t_ns < end_ns - 10000000)
      throw InputError(req.imu, 0, "the IMU log covers [" + seconds(all.front().t_ns) + ", " + seconds(all.back().t_ns) +
                                       "] s but the trajectory span is [" + seconds(begin_ns) + ", " + seconds(end_ns) +
                                       "] s (replay needs the trajectory and IMU of the same recording)");
    // True biases are known only if the trajectory file carries them (EuRoC ground truth).
    const bool has_bias = samples.front().hasVelocityAndBias();
    for (const auto& s : imu.samples) {
      if (!has_bias) break;
      auto it = std::lower_bound(samples.begin(), samples.end(), s.t_ns,
                                 [](const io::TrajectorySample& a, std::int64_t v) { return a.t_ns < v; });
      if (it == samples.end()) --it;
      imu.b_g.push_back(it->b_g);
      imu.b_a.push_back(it->b_a);
    }
  }

  // 4. Output folders (a previous mav0 here is replaced).
  const fs::path mav0 = fs::path(req.out_dir) / "mav0";
  std::error_code ec;
  fs::remove_all(mav0, ec);
  for (const char* sub : {"cam0/data", "cam1/data", "imu0", "state_groundtruth_estimate0"}) fs::create_directories(mav0 / sub, ec);
  if (ec || !fs::is_directory(mav0 / "imu0")) throw InputError(req.out_dir, 0, "cannot create the output folder");
  io::writeEurocCalibration(mav0.string(), rig);
  const auto frame_step = static_cast<std::int64_t>(std::llround(1e9 / rig.camera_rate_hz)) * (req.skip + 1);
  FaultInjector faults(req.faults, begin_ns, toSeconds(frame_step), req.seed);
  std::vector<imu::ImuSample> recorded_imu = faults.recordedImu(imu.samples);
  const auto clock_offset_ns = static_cast<std::int64_t>(std::llround(options.imu_time_offset_ms * 1e6));
  for (imu::ImuSample& s : recorded_imu) s.t_ns += clock_offset_ns;
  io::writeImuCsv((mav0 / "imu0" / "data.csv").string(), recorded_imu);
  io::Trajectory gt;
  for (std::size_t i = 0; i < imu.samples.size(); ++i) {
    const KinematicState s = spline.evaluate(imu.samples[i].t_ns);
    io::TrajectorySample g;
    g.t_ns = imu.samples[i].t_ns;
    g.T_w_b = s.T_w_b;
    if (i < imu.b_g.size()) {
      g.v_w = s.v_w;
      g.b_g = imu.b_g[i];
      g.b_a = imu.b_a[i];
    }
    gt.push_back(g);
  }
  io::writeTrajectoryEuroc((mav0 / "state_groundtruth_estimate0" / "data.csv").string(), gt);

  // 5. Images.
  const RayTable rays[2] = {RayTable(rig.cam[0]), RayTable(rig.cam[1])};
  const LightingChanges lighting(begin_ns, end_ns, options.lighting_change_interval_s, options.lighting_change_magnitude, req.seed);
  const int substeps = req.blur_ms > 0 ? std::max(2, static_cast<int>(std::ceil(req.blur_ms / options.blur_substep_ms)) + 1) : 1;
  std::ostringstream csv[2];
  for (auto& c : csv) c << "#timestamp [ns],filename\n";
  SimSummary summary;
  const std::size_t total = static_cast<std::size_t>((end_ns - begin_ns) / frame_step) + 1;
  // The two cameras of a frame are produced in parallel (each renders with
  // the remaining threads); every pixel depends only on the seed, the frame and
  // the camera, so the output is the same for any thread count.
  const int cam_threads = options.threads >= 2 ? 2 : 1;
  RenderOptions ro;
  ro.threads = std::max(1, options.threads / cam_threads);
  double render_s[2] = {0, 0}, write_s[2] = {0, 0};
  // Renders camera cam's image of the frame at t and writes it as <t>.png
  // (unique even when a fault gives two frames one stamp); false when a
  // fault dropped it.
  const auto produce = [&](int cam, std::int64_t t, float light_scale, double gain, bool* written) {
    RenderOptions cam_ro = ro;
    cam_ro.light_scale = light_scale;
    const auto r0 = std::chrono::steady_clock::now();
    cv::Mat radiance, sub;
    // Motion blur: the mean of sub-frames spread over the exposure, centred on t.
    for (int s = 0; s < substeps; ++s) {
      const double offset_ms = substeps == 1 ? 0.0 : req.blur_ms * (static_cast<double>(s) / (substeps - 1) - 0.5);
      const std::int64_t ts = t + static_cast<std::int64_t>(std::llround(offset_ms * 1e6));
      render(scene, rays[cam], spline.pose(ts) * rig.T_b_c[cam], cam_ro, s == 0 ? &radiance : &sub);
      if (s > 0) radiance += sub;
    }
    if (substeps > 1) radiance /= static_cast<double>(substeps);
    SensorEffects fx;
    fx.gain = options.exposure_gain * gain * (cam == 1 ? 1.0 + options.stereo_brightness_mismatch : 1.0);
    fx.vignetting = options.vignetting;
    fx.noise_sigma = req.noise ? options.image_noise_sigma : 0.0;
    cv::Mat image = sensorImage(radiance, rig.cam[cam], fx,
                                hashCombine(req.seed, static_cast<std::uint64_t>(t) * 2 + static_cast<std::uint64_t>(cam)));
    const auto r1 = std::chrono::steady_clock::now();
    *written = faults.applyToImage(cam, t, &image);
    if (*written)
      io::writePngGray8((mav0 / ("cam" + std::to_string(cam)) / "data" / (std::to_string(t) + ".png")).string(), image,
                      options.png_compression);
    const auto r2 = std::chrono::steady_clock::now();
    render_s[cam] += std::chrono::duration<double>(r1 - r0).count();
    write_s[cam] += std::chrono::duration<double>(r2 - r1).count();
  };
  summary.setup_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  for (std::size_t k = 0; k < total; ++k) {
    const std::int64_t t = begin_ns + static_cast<std::int64_t>(k) * frame_step;
    const double t_rel = toSeconds(t - begin_ns);
    const bool drop_cam1 = Rng(hashCombine(req.seed, 0xd809 + k)).uniform() < req.drop_rate;
    const float light_scale = req.exposure_changes ? lighting.scale(t) : 1.0f;
    double gain = 1.0;
    if (req.exposure_changes)
      gain *= 1.0 + options.exposure_drift_amplitude * std::sin(2 * 3.14159265358979 * t_rel / options.exposure_drift_period_s);
    const std::int64_t stamp = faults.recordedStamp(k, t);
    std::thread second;
    bool written[2] = {false, false};
    if (!drop_cam1) {
      if (cam_threads == 2) second = std::thread(produce, 1, t, light_scale, gain, &written[1]);
      else produce(1, t, light_scale, gain, &written[1]);
    } else {
      ++summary.dropped_cam1;
    }
    produce(0, t, light_scale, gain, &written[0]);
    if (second.joinable()) second.join();
    for (int cam = 0; cam < 2; ++cam) {
      if (written[cam]) csv[cam] << stamp << "," << t << ".png\n";
      summary.fault_dropped[cam] += !written[cam] && !(cam == 1 && drop_cam1);
    }
    ++summary.frames;
    if (progress) progress(k + 1, total);
  }
  summary.render_s = render_s[0] + render_s[1];
  summary.write_s = write_s[0] + write_s[1];
  for (int cam = 0; cam < 2; ++cam) {
    std::ofstream f(mav0 / ("cam" + std::to_string(cam)) / "data.csv");
    f << csv[cam].str();
  }
  writeSimulationYaml((fs::path(req.out_dir) / "simulation.yaml").string(), req, options);
  summary.imu_samples = imu.samples.size();
  summary.position_steps_removed = world.position_steps_removed;
  summary.knot_dt_s = world.knot_dt_s;
  summary.duration_s = toSeconds(end_ns - begin_ns);
  summary.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return summary;
}

}  // namespace edgevio::sim
