// Reading a sequence: a ROS bag against the ASL folder it was exported from
// (the real V1_01_easy micro clip, 95 stereo frames of 752x480), per chunk
// compression and image encoding. Opening (index, IMU, ground truth) and
// reading every stereo frame (both images decoded) are timed apart; the
// per-frame figure is what the pipeline's driver pays.
//   build/release/bench/sequence_read_bench [--benchmark_repetitions=3]
#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include <unistd.h>

#include "edgevio/io/bag_export.h"
#include "edgevio/io/euroc_dataset.h"
#include "edgevio/io/sequence.h"

namespace {

using namespace edgevio;
namespace fs = std::filesystem;

const std::string kClip = std::string(EDGEVIO_DEFAULT_DATA_DIR) + "/euroc/V1_01_easy_micro";

struct Source {
  const char* name;
  io::BagCompression compression;
  io::BagImages images;
};
constexpr Source kBags[] = {{"bag_none_raw", io::BagCompression::kNone, io::BagImages::kRaw},
                            {"bag_bz2_raw", io::BagCompression::kBz2, io::BagImages::kRaw},
                            {"bag_lz4_raw", io::BagCompression::kLz4, io::BagImages::kRaw},
                            {"bag_none_png", io::BagCompression::kNone, io::BagImages::kPng},
                            {"bag_lz4_png", io::BagCompression::kLz4, io::BagImages::kPng}};

/// The bags, exported once into a temporary folder (removed at exit).
const fs::path& bagDir() {
  static const fs::path dir = [] {
    const fs::path d = fs::temp_directory_path() / ("edgevio_read_bench_" + std::to_string(::getpid()));
    io::EurocDataset folder(kClip, io::DatasetOptions{});
    for (const Source& s : kBags) {
      fs::create_directories(d / s.name);
      io::exportBag(folder, (d / s.name / "clip.bag").string(), {s.compression, s.images});
    }
    std::atexit([] { fs::remove_all(bagDir()); });
    return d;
  }();
  return dir;
}

std::string path(int source) { return source < 0 ? kClip : (bagDir() / kBags[source].name / "clip.bag").string(); }

void BM_Open(benchmark::State& state) {
  if (!fs::is_directory(kClip)) return state.SkipWithError((kClip + " is absent (see ../shared/data/README)").c_str());
  const int source = static_cast<int>(state.range(0));
  const std::string p = path(source);
  for (auto _ : state) benchmark::DoNotOptimize(io::openSequence({p, "", {}}, io::DatasetOptions{}));
  state.SetLabel(source < 0 ? "folder" : kBags[source].name);
}

void BM_ReadEveryStereoFrame(benchmark::State& state) {
  if (!fs::is_directory(kClip)) return state.SkipWithError((kClip + " is absent (see ../shared/data/README)").c_str());
  const int source = static_cast<int>(state.range(0));
  const std::unique_ptr<io::Sequence> seq = io::openSequence({path(source), "", {}}, io::DatasetOptions{});
  for (auto _ : state)
    for (std::size_t i = 0; i < seq->frameCount(); ++i) {
      benchmark::DoNotOptimize(seq->leftImage(i));
      benchmark::DoNotOptimize(seq->rightImageLoader(i)());
    }
  state.counters["per_stereo_frame"] =
      benchmark::Counter(static_cast<double>(seq->frameCount()), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.SetLabel(source < 0 ? "folder" : kBags[source].name);
}

}  // namespace

BENCHMARK(BM_Open)->DenseRange(-1, 4)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ReadEveryStereoFrame)->DenseRange(-1, 4)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
