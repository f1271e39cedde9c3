// The three pipeline threads stop cleanly whatever fails: a reader that
// throws halfway (its error reaches the caller after the frames before it),
// and a consumer that throws while both queues are full and both producers
// wait on them (nothing more is read, offline or in real time); and a whole
// run through every thread accounts for every frame (the thread-sanitizer
// stage of scripts/test.sh runs these).
#include "edgevio/pipeline/threaded_pipeline.h"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include <atomic>
#include <chrono>
#include <memory>
#include <stdexcept>
#include <thread>

#include "common/mini_dataset.h"
#include "common/test_support.h"
#include "edgevio/common/error.h"
#include "edgevio/pipeline/run.h"

namespace edgevio::pipeline {
namespace {

using test::TempDir;

/// Reads `inner` and counts the left images read.
class CountingSequence : public io::Sequence {
 public:
  explicit CountingSequence(std::unique_ptr<io::Sequence> inner) : inner_(std::move(inner)) {
    rig_ = inner_->calibration();
    imu_ = inner_->imu();
  }
  std::string name() const override { return inner_->name(); }
  std::string location() const override { return inner_->location(); }
  std::size_t frameCount() const override { return inner_->frameCount(); }
  std::int64_t frameTime(std::size_t i) const override { return inner_->frameTime(i); }
  std::optional<cv::Mat> leftImage(std::size_t i) override {
    ++reads;
    return inner_->leftImage(i);
  }
  std::function<cv::Mat()> rightImageLoader(std::size_t i) const override { return inner_->rightImageLoader(i); }
  std::size_t unreadableImages() const override { return inner_->unreadableImages(); }
  std::size_t cameraFrames(int cam) const override { return inner_->cameraFrames(cam); }

  std::atomic<std::size_t> reads{0};

 private:
  std::unique_ptr<io::Sequence> inner_;
};

struct Fixture {
  explicit Fixture(const test::MiniDatasetSpec& spec)
      : root(test::writeMiniDataset(dir, spec)),
        sequence(io::openSequence({root, "", {}}, io::DatasetOptions{})),
        rect(sequence->calibration(), camera::RectificationOptions{}) {}
  std::vector<std::size_t> allFrames() const {
    std::vector<std::size_t> frames(sequence->frameCount());
    for (std::size_t i = 0; i < frames.size(); ++i) frames[i] = i;
    return frames;
  }
  TempDir dir;
  std::string root;
  std::unique_ptr<io::Sequence> sequence;
  camera::StereoRectifier rect;
  vision::VisionOptions vision;
};

test::MiniDatasetSpec patterned(int frames, std::int64_t frame_dt_ns) {
  test::MiniDatasetSpec spec;
  spec.frames = frames;
  spec.patterned = true;
  spec.frame_dt_ns = frame_dt_ns;
  return spec;
}

class ReaderError : public ::testing::TestWithParam<bool> {};

TEST_P(ReaderError, AnImageThatBreaksHalfwayEndsTheRunWithItsNameAfterTheFramesBeforeIt) {
  const bool realtime = GetParam();
  Fixture f(patterned(12, 50'000'000));
  // Frame 6's left image at another size than the calibration's: the reader throws.
  const std::string broken = f.root + "/mav0/cam0/data/" + std::to_string(f.sequence->frameTime(6)) + ".png";
  ASSERT_TRUE(cv::imwrite(broken, cv::Mat(10, 10, CV_8UC1, cv::Scalar(128))));
  std::vector<std::int64_t> consumed;
  try {
    runThreaded(*f.sequence, f.allFrames(), f.rect, f.vision, realtime,
                [&](PipelineFrame p) { consumed.push_back(p.t_ns); });
    FAIL() << "the broken image did not stop the run";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(broken), std::string::npos) << e.what();
  }
  // Offline every frame before the broken one arrives, in order; in real
  // time some may have been dropped, never reordered or invented.
  if (!realtime) {
    EXPECT_EQ(consumed.size(), 6u);
  }
  EXPECT_LE(consumed.size(), 6u);
  for (std::size_t k = 0; k < consumed.size(); ++k) {
    EXPECT_LT(consumed[k], f.sequence->frameTime(6));
    if (k > 0) {
      EXPECT_GT(consumed[k], consumed[k - 1]);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Pipeline, ReaderError, ::testing::Values(false, true),
                         [](const ::testing::TestParamInfo<bool>& p) { return p.param ? "realtime" : "offline"; });

TEST(ConsumerError, WithBothQueuesFullStopsBothProducersAndNothingMoreIsRead) {
  Fixture f(patterned(30, 50'000'000));
  const std::vector<std::size_t> frames = f.allFrames();
  CountingSequence sequence(std::move(f.sequence));
  // Offline the producers block when the queues are full: the frame being
  // consumed, two in each queue of capacity two, and one in each producer's
  // hands waiting to push make 7 frames read, and then no more until the
  // consumer takes one.
  constexpr std::size_t kHeld = 1 + 2 + 1 + 2 + 1;
  std::size_t reads_at_error = 0;
  try {
    runThreaded(sequence, frames, f.rect, f.vision, false, [&](PipelineFrame) {
      const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(30);
      while (sequence.reads < kHeld && std::chrono::steady_clock::now() < give_up)
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
      std::this_thread::sleep_for(std::chrono::milliseconds(50));  // a producer that does not block would read on
      reads_at_error = sequence.reads;
      throw std::runtime_error("consumer failed");
    });
    FAIL() << "the consumer's error did not reach the caller";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "consumer failed");
  }
  EXPECT_EQ(reads_at_error, kHeld);
  EXPECT_EQ(sequence.reads, kHeld) << "the driver read on after the consumer had stopped";
}

TEST(ConsumerError, InRealTimeTheDriverStopsWaitingForTheNextFrame) {
  // Frames a second apart: a driver that kept its schedule after the error
  // would read all 20 over 19 s before the caller heard of it.
  Fixture f(patterned(20, 1'000'000'000));
  const std::vector<std::size_t> frames = f.allFrames();
  CountingSequence sequence(std::move(f.sequence));
  std::size_t reads_at_error = 0;
  EXPECT_THROW(runThreaded(sequence, frames, f.rect, f.vision, true,
                           [&](PipelineFrame) {
                             reads_at_error = sequence.reads;
                             throw std::runtime_error("consumer failed");
                           }),
               std::runtime_error);
  EXPECT_GE(reads_at_error, 1u);
  EXPECT_EQ(sequence.reads, reads_at_error);
}

class WholeRun : public ::testing::TestWithParam<bool> {};

TEST_P(WholeRun, ThroughEveryThreadAccountsForEveryFrame) {
  // The full system on 12 small frames: the driver reads, the second thread
  // builds pyramids, this one tracks, decodes keyframes' right images,
  // estimates and writes. In real time a frame may be dropped, and counted.
  TempDir dir;
  const std::string mini = test::writeMiniDataset(dir, patterned(12, 50'000'000));
  RunRequest req(mini, dir.file("out"));
  req.realtime = GetParam();
  const RunSummary s = run(req, Config{});
  EXPECT_EQ(s.frames_to_process, 12u);
  EXPECT_EQ(s.frames + s.dropped_frames + s.unreadable_frames, 12u);
  EXPECT_EQ(s.unaccountedFrames(), 0);
  if (!req.realtime) {
    EXPECT_EQ(s.dropped_frames, 0u);
  }
}

INSTANTIATE_TEST_SUITE_P(Pipeline, WholeRun, ::testing::Values(false, true),
                         [](const ::testing::TestParamInfo<bool>& p) { return p.param ? "realtime" : "offline"; });

}  // namespace
}  // namespace edgevio::pipeline
