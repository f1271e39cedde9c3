// Sensor faults: the spec a user writes, when each fault is active, and what
// it does to an image, a stamp and the IMU log.
#include "edgevio/sim/faults.h"

#include <gtest/gtest.h>

#include "common/test_support.h"

namespace edgevio::sim {
namespace {

constexpr std::int64_t kT0 = 1000000000000LL;
constexpr double kFrame = 0.05;  // 20 Hz
constexpr std::int64_t kFrameNs = 50000000;

std::int64_t at(double s) { return kT0 + std::llround(s * 1e9); }

TEST(Faults, SpecsParseAndRoundTrip) {
  const Fault f = parseFault("saturated:at=2.5,for=0.1,every=5,size=3");
  EXPECT_EQ(f.kind, FaultKind::kSaturated);
  EXPECT_EQ(f.at_s, 2.5);
  EXPECT_EQ(f.for_s, 0.1);
  EXPECT_EQ(f.every_s, 5.0);
  EXPECT_EQ(f.size, 3.0);
  const Fault back = parseFault(faultSpec(f));
  EXPECT_EQ(back.kind, f.kind);
  EXPECT_EQ(back.at_s, f.at_s);
  EXPECT_EQ(back.every_s, f.every_s);
  EXPECT_EQ(parseFault("black").kind, FaultKind::kBlack);
  EXPECT_EQ(parseFault("black").at_s, 0.0);
  // Defaults of the magnitudes, where size is not given.
  EXPECT_EQ(parseFault("stamp_jump").magnitude(), 100.0);
  EXPECT_EQ(parseFault("stamp_jump:size=20").magnitude(), 20.0);
}

TEST(Faults, BadSpecsAreExplained) {
  test::expectInputError([] { parseFault("blak:at=1"); }, {"--fault blak:at=1", "unknown kind 'blak'", "black"});
  test::expectInputError([] { parseFault("black:start=1"); }, {"unknown key 'start'", "at, for, every"});
  test::expectInputError([] { parseFault("black:at"); }, {"'at' is not key=number"});
  test::expectInputError([] { parseFault("black:at=x"); }, {"'at=x' is not key=number"});
  test::expectInputError([] { parseFault("black:for=-1"); }, {"for must be >= 0"});
  test::expectInputError([] { parseFault("black:for=2,every=2"); }, {"for must be shorter than every"});
}

TEST(Faults, ActiveInTheirWindowsOnly) {
  const Fault f = parseFault("black:at=1,for=0.5,every=2");
  const auto ns = [](double s) { return std::llround(s * 1e9); };
  for (const double t : {1.0, 1.2, 1.49, 3.0, 3.49, 7.0}) EXPECT_TRUE(f.active(ns(t), kFrameNs)) << t;
  for (const double t : {0.0, 0.99, 1.5, 2.9, 3.5, 4.99}) EXPECT_FALSE(f.active(ns(t), kFrameNs)) << t;
  // A window of length 0 is one frame long, exactly (2.7 and 2.75 are not
  // one frame apart in doubles).
  const Fault once = parseFault("black:at=2.7");
  EXPECT_TRUE(once.active(ns(2.7), kFrameNs));
  EXPECT_TRUE(once.active(ns(2.749), kFrameNs));
  EXPECT_FALSE(once.active(ns(2.75), kFrameNs));
  EXPECT_FALSE(once.active(ns(3.7), kFrameNs));
}

cv::Mat ramp() {
  cv::Mat m(8, 10, CV_8U);
  for (int v = 0; v < m.rows; ++v)
    for (int u = 0; u < m.cols; ++u) m.at<std::uint8_t>(v, u) = static_cast<std::uint8_t>(10 * u + v);
  return m;
}

TEST(Faults, ImageFaults) {
  FaultInjector inj({parseFault("black:at=0.1"), parseFault("saturated:at=0.2"), parseFault("occluded:at=0.3"),
                     parseFault("frozen:at=0.4,for=0.1"), parseFault("drop_left:at=0.6"), parseFault("drop_right:at=0.7")},
                    kT0, kFrame, 1);
  const cv::Mat original = ramp();
  cv::Mat img = original.clone();
  ASSERT_TRUE(inj.applyToImage(0, at(0.0), &img));  // no fault: unchanged
  EXPECT_EQ(cv::norm(img, original, cv::NORM_INF), 0.0);
  img = original.clone();
  ASSERT_TRUE(inj.applyToImage(0, at(0.1), &img));
  EXPECT_EQ(cv::countNonZero(img), 0);
  img = original.clone();
  ASSERT_TRUE(inj.applyToImage(0, at(0.2), &img));
  EXPECT_EQ(img.at<std::uint8_t>(1, 2), 4 * 21);  // x4, below the clip
  EXPECT_EQ(img.at<std::uint8_t>(7, 9), 255);      // 97 x 4 clipped
  img = original.clone();
  ASSERT_TRUE(inj.applyToImage(0, at(0.3), &img));
  EXPECT_EQ(img.at<std::uint8_t>(3, 4), 12);                       // left half dark
  EXPECT_EQ(img.at<std::uint8_t>(3, 5), original.at<std::uint8_t>(3, 5));  // right half untouched
  // Frozen: the last image delivered, the occluded one of t = 0.3.
  const cv::Mat occluded = img.clone();
  cv::Mat other(8, 10, CV_8U, cv::Scalar(200));
  ASSERT_TRUE(inj.applyToImage(0, at(0.45), &other));
  EXPECT_EQ(cv::norm(other, occluded, cv::NORM_INF), 0.0);
  img = original.clone();
  EXPECT_FALSE(inj.applyToImage(0, at(0.6), &img));
  EXPECT_TRUE(inj.applyToImage(1, at(0.6), &img));
  EXPECT_FALSE(inj.applyToImage(1, at(0.7), &img));
}

TEST(Faults, StampFaults) {
  FaultInjector inj({parseFault("stamp_jump:at=0.2,for=0.1"), parseFault("stamp_duplicate:at=0.5"),
                     parseFault("stamp_jitter:at=1,for=1,size=2")},
                    kT0, kFrame, 7);
  EXPECT_EQ(inj.recordedStamp(0, at(0.0)), at(0.0));
  EXPECT_EQ(inj.recordedStamp(4, at(0.2)), at(0.2) + 100000000);
  EXPECT_EQ(inj.recordedStamp(5, at(0.25)), at(0.25) + 100000000);
  EXPECT_EQ(inj.recordedStamp(6, at(0.3)), at(0.3));  // the window is [0.2, 0.3)
  EXPECT_EQ(inj.recordedStamp(9, at(0.45)), at(0.45));
  EXPECT_EQ(inj.recordedStamp(10, at(0.5)), at(0.45));  // its predecessor's stamp
  // Jitter: 2 ms std. dev., 20 frames: none beyond 5 sigma, not all zero, the same again for the same seed.
  FaultInjector again({parseFault("stamp_jitter:at=1,for=1,size=2")}, kT0, kFrame, 7);
  int moved = 0;
  for (std::size_t k = 20; k < 40; ++k) {
    const std::int64_t t = at(0.05 * static_cast<double>(k));
    const std::int64_t s = inj.recordedStamp(k, t);
    EXPECT_LT(std::llabs(s - t), 10000000) << k;
    EXPECT_EQ(again.recordedStamp(k, t), s);
    moved += s != t;
  }
  EXPECT_EQ(moved, 20);
}

TEST(Faults, ImuFaults) {
  std::vector<imu::ImuSample> truth;
  for (int i = 0; i < 400; ++i) truth.push_back({at(0.005 * i), Vec3(0.1, 0.2, 0.3), Vec3(0, 0, 9.81)});  // 2 s at 200 Hz
  const FaultInjector dropout({parseFault("imu_dropout:at=0.5,for=0.25")}, kT0, kFrame, 1);
  const std::vector<imu::ImuSample> kept = dropout.recordedImu(truth);
  // [0.5, 0.75) at 200 Hz: 50 readings.
  EXPECT_EQ(kept.size(), truth.size() - 50);
  for (const imu::ImuSample& s : kept) EXPECT_FALSE(s.t_ns >= at(0.5) && s.t_ns < at(0.75)) << s.t_ns;
  // One spike a second, one reading each.
  const FaultInjector spikes({parseFault("imu_spike:at=0.5,every=1,size=2")}, kT0, kFrame, 1);
  const std::vector<imu::ImuSample> spiked = spikes.recordedImu(truth);
  ASSERT_EQ(spiked.size(), truth.size());
  int hit = 0;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    if (spiked[i].gyro == truth[i].gyro) continue;
    ++hit;
    EXPECT_NEAR((spiked[i].gyro - truth[i].gyro).x(), 2.0, 1e-12);
    EXPECT_NEAR((spiked[i].accel - truth[i].accel).z(), 2.0 * 9.81, 1e-12);
  }
  EXPECT_EQ(hit, 2);  // at 0.5 s and 1.5 s
}

}  // namespace
}  // namespace edgevio::sim
