#include "edgevio/sim/faults.h"

#include <algorithm>
#include <cmath>

#include "edgevio/common/error.h"
#include "edgevio/common/format.h"
#include "edgevio/common/time.h"
#include "edgevio/sim/imu_synth.h"
#include "edgevio/sim/random.h"

namespace edgevio::sim {

namespace {

/// What a saturated-frame fault leaves of the scene: a frame exposed this
/// many times too long (a sudden light, the sun) clips most of it at 255.
constexpr double kDefaultOverexposure = 4.0;
/// The grey of the occluded half: a dark, textureless object close to the lens.
constexpr int kOccluderGrey = 12;

double defaultSize(FaultKind kind) {
  switch (kind) {
    case FaultKind::kSaturated: return kDefaultOverexposure;
    case FaultKind::kImuSpike: return 3.0;
    case FaultKind::kStampJitter: return 2.0;
    case FaultKind::kStampJump: return 100.0;
    default: return 0.0;
  }
}

std::string fail(const std::string& spec, const std::string& why) {
  return "--fault " + spec + ": " + why + " (expected KIND[:key=value,...]; kinds: " + options::choiceList(kFaultKindChoices) +
         "; keys: at, for, every [s] and size)";
}

}  // namespace

bool Fault::active(std::int64_t t_rel_ns, std::int64_t min_length_ns) const {
  const std::int64_t at = toNanoseconds(at_s), every = toNanoseconds(every_s);
  const std::int64_t length = std::max(toNanoseconds(for_s), min_length_ns);
  if (t_rel_ns < at) return false;
  const std::int64_t since = every > 0 ? (t_rel_ns - at) % every : t_rel_ns - at;
  return since < length;
}

double Fault::magnitude() const { return size != 0.0 ? size : defaultSize(kind); }

Fault parseFault(const std::string& spec) {
  Fault f;
  const std::size_t colon = spec.find(':');
  const std::string kind = spec.substr(0, colon);
  if (!options::parseChoice(kFaultKindChoices, kind, &f.kind)) throw InputError(fail(spec, "unknown kind '" + kind + "'"));
  if (colon == std::string::npos) return f;
  std::size_t pos = colon + 1;
  while (pos <= spec.size()) {
    const std::size_t end = std::min(spec.find(',', pos), spec.size());
    const std::string item = spec.substr(pos, end - pos);
    const std::size_t eq = item.find('=');
    double value = 0.0;
    if (eq == std::string::npos || !options::parseNumber(item.substr(eq + 1), &value))
      throw InputError(fail(spec, "'" + item + "' is not key=number"));
    const std::string key = item.substr(0, eq);
    double* field = key == "at" ? &f.at_s : key == "for" ? &f.for_s : key == "every" ? &f.every_s : key == "size" ? &f.size : nullptr;
    if (!field) throw InputError(fail(spec, "unknown key '" + key + "'"));
    if (value < 0.0) throw InputError(fail(spec, key + " must be >= 0"));
    *field = value;
    pos = end + 1;
  }
  if (f.every_s > 0.0 && f.for_s >= f.every_s) throw InputError(fail(spec, "for must be shorter than every"));
  return f;
}

std::string faultSpec(const Fault& f) {
  return formatText("%s:at=%s,for=%s,every=%s,size=%s", options::nameOf(kFaultKindChoices, f.kind),
                    options::formatNumber(f.at_s).c_str(), options::formatNumber(f.for_s).c_str(),
                    options::formatNumber(f.every_s).c_str(), options::formatNumber(f.size).c_str());
}

FaultInjector::FaultInjector(std::vector<Fault> faults, std::int64_t t0_ns, double frame_period_s, std::uint64_t seed)
    : faults_(std::move(faults)), t0_ns_(t0_ns), frame_period_ns_(toNanoseconds(frame_period_s)), seed_(seed) {}

bool FaultInjector::any(FaultKind kind, std::int64_t t_ns, std::int64_t min_length_ns, const Fault** which) const {
  for (const Fault& f : faults_)
    if (f.kind == kind && f.active(t_ns - t0_ns_, min_length_ns)) {
      if (which) *which = &f;
      return true;
    }
  return false;
}

bool FaultInjector::applyToImage(int cam, std::int64_t t_ns, cv::Mat* image) {
  const std::int64_t frame = frame_period_ns_;
  if (any(cam == 0 ? FaultKind::kDropLeft : FaultKind::kDropRight, t_ns, frame)) return false;
  if (any(FaultKind::kFrozen, t_ns, frame)) {
    if (!last_delivered_[cam].empty()) last_delivered_[cam].copyTo(*image);
    return true;
  }
  const Fault* f = nullptr;
  if (any(FaultKind::kBlack, t_ns, frame)) image->setTo(0);
  if (any(FaultKind::kSaturated, t_ns, frame, &f)) image->convertTo(*image, CV_8U, f->magnitude());
  if (any(FaultKind::kOccluded, t_ns, frame)) (*image)(cv::Rect(0, 0, image->cols / 2, image->rows)).setTo(kOccluderGrey);
  const bool freezes = std::any_of(faults_.begin(), faults_.end(), [](const Fault& g) { return g.kind == FaultKind::kFrozen; });
  if (freezes) image->copyTo(last_delivered_[cam]);
  return true;
}

std::int64_t FaultInjector::recordedStamp(std::size_t k, std::int64_t t_ns) {
  std::int64_t stamp = t_ns;
  const Fault* f = nullptr;
  if (any(FaultKind::kStampJitter, t_ns, frame_period_ns_, &f))
    stamp += std::llround(f->magnitude() * 1e6 * Rng(hashCombine(seed_, 0x5a17 + k)).gaussian());
  if (any(FaultKind::kStampJump, t_ns, frame_period_ns_, &f)) stamp += std::llround(f->magnitude() * 1e6);
  if (any(FaultKind::kStampDuplicate, t_ns, frame_period_ns_) && last_stamp_ >= 0) stamp = last_stamp_;
  last_stamp_ = stamp;
  return stamp;
}

std::vector<imu::ImuSample> FaultInjector::recordedImu(const std::vector<imu::ImuSample>& truth) const {
  std::vector<imu::ImuSample> out;
  out.reserve(truth.size());
  // The IMU period: a window shorter than that still hits one reading.
  const std::int64_t reading =
      truth.size() < 2 ? 0 : (truth.back().t_ns - truth.front().t_ns) / static_cast<std::int64_t>(truth.size() - 1);
  for (std::size_t i = 0; i < truth.size(); ++i) {
    imu::ImuSample s = truth[i];
    if (any(FaultKind::kImuDropout, s.t_ns, reading)) continue;
    const Fault* f = nullptr;
    if (any(FaultKind::kImuSpike, s.t_ns, reading, &f)) {
      s.gyro += Vec3::Constant(f->magnitude());
      s.accel += Vec3::Constant(f->magnitude() * kGravity);
    }
    out.push_back(s);
  }
  return out;
}

}  // namespace edgevio::sim
