#pragma once
// Faults a real rig produces, injected into a rendered sequence (`edgevio
// simulate --fault KIND[:key=value,...]`): broken images, lost or wrong IMU
// readings, wrong timestamps. Each fault is active in windows of time
// measured from the first frame: [at, at + for), at least one frame (or one
// IMU reading) long, repeated every `every` seconds when that is given. The rendering
// itself (poses, scene, ground truth) is untouched: a fault changes only
// what the sensors report.
#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "edgevio/common/options.h"
#include "edgevio/imu/imu_types.h"

namespace edgevio::sim {

enum class FaultKind {
  kBlack,
  kFrozen,
  kSaturated,
  kOccluded,
  kDropLeft,
  kDropRight,
  kImuDropout,
  kImuSpike,
  kStampJitter,
  kStampJump,
  kStampDuplicate
};
inline constexpr options::Choice<FaultKind> kFaultKindChoices[] = {
    {FaultKind::kBlack, "black", "both images black (a covered lens, a camera reset)"},
    {FaultKind::kFrozen, "frozen", "both images repeat the last ones delivered (a stalled driver)"},
    {FaultKind::kSaturated, "saturated", "both images overexposed: brightness x size (default 4), clipped at 255"},
    {FaultKind::kOccluded, "occluded", "the left half of both images dark (something in front of the rig)"},
    {FaultKind::kDropLeft, "drop_left", "no left image (file and row absent)"},
    {FaultKind::kDropRight, "drop_right", "no right image (file and row absent)"},
    {FaultKind::kImuDropout, "imu_dropout", "no IMU readings"},
    {FaultKind::kImuSpike, "imu_spike", "each reading off by size (default 3) rad/s on every gyroscope axis and size g on every accelerometer axis"},
    {FaultKind::kStampJitter, "stamp_jitter", "image stamps off by a normal error of size (default 2) ms std. dev."},
    {FaultKind::kStampJump, "stamp_jump", "image stamps late by size (default 100) ms"},
    {FaultKind::kStampDuplicate, "stamp_duplicate", "a frame stamped as its predecessor"}};

struct Fault {
  FaultKind kind = FaultKind::kBlack;
  double at_s = 0.0;     ///< first window's start, after the first frame [s]
  double for_s = 0.0;    ///< window length [s]; 0: one frame (or one IMU reading)
  double every_s = 0.0;  ///< period of the windows [s]; 0: one window
  double size = 0.0;     ///< the kind's magnitude (see kFaultKindChoices); 0: its default

  /// Whether t_rel_ns (after the first frame) lies in a window; a window
  /// shorter than `min_length_ns` is widened to it. In whole nanoseconds, so
  /// that a one-frame window holds exactly one frame.
  bool active(std::int64_t t_rel_ns, std::int64_t min_length_ns) const;
  /// size, or the kind's default where size is 0.
  double magnitude() const;
};

/// Parses "KIND[:key=value,...]" (keys at, for, every, size); InputError
/// naming the spec, the kinds or the keys on a mistake.
Fault parseFault(const std::string& spec);
/// The spec parseFault reads back.
std::string faultSpec(const Fault& f);

/// The faults of a simulation, applied to what its sensors report.
class FaultInjector {
 public:
  FaultInjector(std::vector<Fault> faults, std::int64_t t0_ns, double frame_period_s, std::uint64_t seed);

  /// Applies the image faults to camera cam's image of the frame at t_ns.
  /// Returns false when the image is dropped (not written).
  bool applyToImage(int cam, std::int64_t t_ns, cv::Mat* image);
  /// The stamp frame k (time t_ns) is recorded with.
  std::int64_t recordedStamp(std::size_t k, std::int64_t t_ns);
  /// The IMU log as recorded: readings removed or spiked.
  std::vector<imu::ImuSample> recordedImu(const std::vector<imu::ImuSample>& truth) const;

 private:
  bool any(FaultKind kind, std::int64_t t_ns, std::int64_t min_length_ns, const Fault** which = nullptr) const;

  std::vector<Fault> faults_;
  std::int64_t t0_ns_;
  std::int64_t frame_period_ns_;
  std::uint64_t seed_;
  cv::Mat last_delivered_[2];  ///< each camera's last image written (kept only for frozen faults)
  std::int64_t last_stamp_ = -1;
};

}  // namespace edgevio::sim
