// Simulator speed (issue #4): per-component time of one 752x480 camera image
// (ray casting, sensor model, PNG encoding) on the EuRoC calibration, and the
// whole `simulate` loop in stereo frames per second.
#include <benchmark/benchmark.h>

#include <opencv2/imgcodecs.hpp>

#include <filesystem>

#include "edgevio/io/calibration_io.h"
#include "edgevio/io/png_writer.h"
#include "edgevio/sim/renderer.h"
#include "edgevio/sim/sensor_model.h"
#include "edgevio/sim/simulator.h"
#include "edgevio/sim/trajectory_source.h"

namespace {

using namespace edgevio;

struct Fixture {
  camera::StereoRig rig = io::eurocDefaultRig();
  io::Trajectory samples = sim::scenarioSamples("figure8", 12.0, 1.0, rig.T_b_c[0]);
  sim::Scene scene;
  sim::RayTable rays{rig.cam[0]};
  Fixture() {
    std::vector<Vec3> path;
    for (const auto& s : samples) path.push_back(s.T_w_b.translation());
    scene = sim::buildScene(path, sim::SceneOptions{}, 1);
  }
  geometry::SE3 cameraPose(std::size_t i) const { return samples[i % samples.size()].T_w_b * rig.T_b_c[0]; }
};

const Fixture& fixture() {
  static const Fixture f;
  return f;
}

void BM_RayCastImage(benchmark::State& state) {
  const Fixture& f = fixture();
  sim::RenderOptions o;
  o.threads = static_cast<int>(state.range(0));
  cv::Mat radiance;
  std::size_t i = 300;
  for (auto _ : state) {
    sim::render(f.scene, f.rays, f.cameraPose(i), o, &radiance);
    i += 37;
    benchmark::DoNotOptimize(radiance.data);
  }
  state.SetLabel(std::to_string(o.threads) + " thread(s), 752x480");
}
BENCHMARK(BM_RayCastImage)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_SensorModel(benchmark::State& state) {
  const Fixture& f = fixture();
  cv::Mat radiance;
  sim::render(f.scene, f.rays, f.cameraPose(400), sim::RenderOptions{}, &radiance);
  sim::SensorEffects fx;
  fx.noise_sigma = 2.0;
  fx.vignetting = 0.2;
  std::uint64_t key = 0;
  for (auto _ : state) benchmark::DoNotOptimize(sim::sensorImage(radiance, f.rig.cam[0], fx, ++key).data);
}
BENCHMARK(BM_SensorModel)->Unit(benchmark::kMillisecond);

void BM_PngEncode(benchmark::State& state) {
  const Fixture& f = fixture();
  cv::Mat radiance;
  sim::render(f.scene, f.rays, f.cameraPose(400), sim::RenderOptions{}, &radiance);
  const cv::Mat img = sim::sensorImage(radiance, f.rig.cam[0], {0.65, 0.2, 2.0}, 1);
  std::vector<uchar> buf;
  const std::vector<int> params = {cv::IMWRITE_PNG_COMPRESSION, static_cast<int>(state.range(0)),
                                    cv::IMWRITE_PNG_STRATEGY, static_cast<int>(state.range(1))};
  for (auto _ : state) cv::imencode(".png", img, buf, params);
  state.SetLabel("level " + std::to_string(state.range(0)) + ", strategy " + std::to_string(state.range(1)) + ", " +
                 std::to_string(buf.size() / 1024) + " KiB");
}
// Strategy 0 = default, 2 = Huffman only, 3 = RLE (zlib's Z_* strategies).
BENCHMARK(BM_PngEncode)->Args({1, 0})->Args({1, 2})->Unit(benchmark::kMillisecond);

/// edgevio's own writer (fixed Up filter, zlib level 1): what the simulator uses.
void BM_PngWriteGray8(benchmark::State& state) {
  const Fixture& f = fixture();
  cv::Mat radiance;
  sim::render(f.scene, f.rays, f.cameraPose(400), sim::RenderOptions{}, &radiance);
  const cv::Mat img = sim::sensorImage(radiance, f.rig.cam[0], {0.65, 0.2, 2.0}, 1);
  const std::string path = (std::filesystem::temp_directory_path() / "edgevio_bench.png").string();
  for (auto _ : state) io::writePngGray8(path, img, 1);
  state.SetLabel(std::to_string(std::filesystem::file_size(path) / 1024) + " KiB");
  std::filesystem::remove(path);
}
BENCHMARK(BM_PngWriteGray8)->Unit(benchmark::kMillisecond);

/// The whole simulate loop: 8 s of the figure8 scenario (161 stereo frames), no blur.
void BM_SimulateStereoFrames(benchmark::State& state) {
  const std::string out = (std::filesystem::temp_directory_path() / "edgevio_bench_sim").string();
  sim::SimRequest r;
  r.out_dir = out;
  r.scenario = "figure8";
  r.start_s = 2.0;
  r.duration_s = 8.0;
  sim::SimOptions o;
  std::size_t frames = 0;
  double render = 0, write = 0, setup = 0, loop = 0;
  for (auto _ : state) {
    const sim::SimSummary s = sim::simulate(r, o);
    frames += s.frames;
    render += s.render_s;
    write += s.write_s;
    setup += s.setup_s;
    loop += s.wall_s - s.setup_s;
  }
  state.counters["setup_s"] = setup;
  state.counters["loop_stereo_frames_per_s"] = static_cast<double>(frames) / loop;
  state.counters["stereo_frames_per_s"] = benchmark::Counter(static_cast<double>(frames), benchmark::Counter::kIsRate);
  state.counters["render_ms_per_frame"] = 1e3 * render / static_cast<double>(frames);
  state.counters["write_ms_per_frame"] = 1e3 * write / static_cast<double>(frames);
  std::filesystem::remove_all(out);
}
BENCHMARK(BM_SimulateStereoFrames)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
