#include "edgevio/io/euroc_dataset.h"

#include <opencv2/imgcodecs.hpp>

#include <cmath>
#include <filesystem>

#include "edgevio/common/error.h"
#include "edgevio/common/format.h"
#include "edgevio/common/table_reader.h"
#include "edgevio/common/time.h"
#include "edgevio/imu/imu_glitches.h"
#include "edgevio/io/calibration_io.h"
#include "edgevio/io/imu_io.h"
#include "edgevio/io/png_reader.h"

namespace edgevio::io {

namespace fs = std::filesystem;

EurocDataset::EurocDataset(const std::string& root, const DatasetOptions& options) : options_(options) {
  const fs::path r(root);
  if (!fs::is_directory(r)) throw InputError(root, 0, "dataset folder not found (expected an EuRoC ASL folder with mav0/)");
  fs::path mav0 = (fs::is_directory(r / "mav0") ? r / "mav0" : r).lexically_normal();
  if (mav0.filename().empty()) mav0 = mav0.parent_path();  // a trailing separator
  mav0_ = mav0.string();
  for (const char* sub : {"cam0", "cam1", "imu0"})
    if (!fs::is_directory(fs::path(mav0_) / sub))
      throw InputError(mav0_, 0, std::string("missing folder '") + sub + "' (expected the EuRoC ASL layout mav0/{cam0,cam1,imu0})");

  rig_ = loadEurocCalibration(mav0_);
  const std::vector<ImageRecord> left = readImageList(0);
  const std::vector<ImageRecord> right = readImageList(1);
  pairFrames(left, right);
  readImu();
  const fs::path gt = fs::path(mav0_) / "state_groundtruth_estimate0" / "data.csv";
  if (fs::exists(gt)) ground_truth_ = readTrajectory(gt.string());
}

std::vector<ImageRecord> EurocDataset::readImageList(int cam) {
  const fs::path dir = fs::path(mav0_) / ("cam" + std::to_string(cam));
  TableReader r((dir / "data.csv").string(), TableReader::Separator::kComma);
  std::vector<ImageRecord> list;
  std::int64_t last = -1;
  while (r.next()) {
    r.requireFields(2, "timestamp [ns],filename");
    ImageRecord rec;
    rec.t_ns = r.integer(0);
    rec.line = r.line();
    ++rows_[cam];
    if (rec.t_ns <= last) {
      ++unreadable_[cam];
      warnings_.push_back(r.path() + ":" + std::to_string(r.line()) + ": " + (rec.t_ns == last ? "duplicate" : "decreasing") +
                          " timestamp " + std::to_string(rec.t_ns) + ", frame skipped (image rows must be in increasing time order)");
      continue;
    }
    last = rec.t_ns;
    const std::string& name = r.field(1);
    if (name.empty() || name.find("..") != std::string::npos || name[0] == '/')
      r.fail("filename '" + name + "' must be a plain file name inside data/");
    rec.path = (dir / "data" / name).string();
    if (!fs::is_regular_file(rec.path)) {
      ++unreadable_[cam];
      warnings_.push_back(r.path() + ":" + std::to_string(r.line()) + ": image file missing, frame skipped: " + rec.path);
      continue;
    }
    list.push_back(rec);
  }
  return list;
}

void EurocDataset::pairFrames(const std::vector<ImageRecord>& left, const std::vector<ImageRecord>& right) {
  std::vector<std::int64_t> tl, tr;
  for (const ImageRecord& r : left) tl.push_back(r.t_ns);
  for (const ImageRecord& r : right) tr.push_back(r.t_ns);
  for (const auto& [i, j] : pairStereo(tl, tr, toNanoseconds(options_.stereo_sync_tolerance_s), unpaired_))
    pairs_.push_back({left[i].t_ns, left[i], right[j]});
  for (int cam = 0; cam < 2; ++cam)
    if (unpaired_[cam] > 0)
      warnings_.push_back("cam" + std::to_string(cam) + ": " + std::to_string(unpaired_[cam]) +
                          " frame(s) without a partner in the other camera within " +
                          std::to_string(options_.stereo_sync_tolerance_s) + " s, skipped");
}

void EurocDataset::readImu() {
  const std::string path = (fs::path(mav0_) / "imu0" / "data.csv").string();
  imu_ = readImuCsv(path, options_.imu_gap_warning_s, &warnings_);
  prepareImuLog(&imu_, rig_, options_, path, &warnings_);
}

double EurocDataset::imuRateHz() const {
  if (imu_.size() < 2) return 0.0;
  return static_cast<double>(imu_.size() - 1) / toSeconds(imu_.back().t_ns - imu_.front().t_ns);
}

double EurocDataset::durationSeconds() const {
  if (pairs_.size() < 2) return 0.0;
  return toSeconds(pairs_.back().t_ns - pairs_.front().t_ns);
}

cv::Mat decodeGrayImage(const std::string& path) {
  cv::Mat fast = readPngGray8(path);
  if (!fast.empty()) return fast;
  try {
    return cv::imread(path, cv::IMREAD_GRAYSCALE);
  } catch (const cv::Exception&) {
    return {};
  }
}

std::optional<cv::Mat> EurocDataset::loadImage(std::size_t i, int cam) {
  const StereoRecord& rec = pairs_.at(i);
  return loadImage(cam, cam == 0 ? rec.left : rec.right);
}

std::optional<cv::Mat> EurocDataset::loadImage(int cam, const ImageRecord& rec) {
  cv::Mat img = decodeGrayImage(rec.path);
  if (img.empty()) {
    ++unreadable_[cam];
    warnings_.push_back(rec.path + ": image does not decode, frame skipped");
    return std::nullopt;
  }
  const camera::CameraModel& m = rig_.cam[cam];
  if (img.cols != m.width || img.rows != m.height)
    throw InputError(rec.path, 0,
                     "image is " + std::to_string(img.cols) + "x" + std::to_string(img.rows) + ", but cam" +
                         std::to_string(cam) + "/sensor.yaml says " + std::to_string(m.width) + "x" +
                         std::to_string(m.height) + " (fix the resolution in the calibration or the images)");
  return img;
}

std::string EurocDataset::name() const { return fs::path(mav0_).parent_path().filename().string(); }

std::string EurocDataset::location() const { return fs::absolute(fs::path(mav0_).parent_path()).lexically_normal().string(); }

std::function<cv::Mat()> EurocDataset::rightImageLoader(std::size_t i) const {
  return [path = pairs_.at(i).right.path, width = rig_.cam[1].width, height = rig_.cam[1].height] {
    cv::Mat raw = decodeGrayImage(path);
    return raw.cols == width && raw.rows == height ? raw : cv::Mat();
  };
}

void prepareImuLog(std::vector<imu::ImuSample>* imu, const camera::StereoRig& rig, const DatasetOptions& options,
                   const std::string& where, std::vector<std::string>* warnings) {
  const std::int64_t clock_offset_ns = toNanoseconds(rig.imu_time_offset_s + options.imu_time_offset_ms * 1e-3);
  for (imu::ImuSample& s : *imu) s.t_ns -= clock_offset_ns;
  const std::vector<std::size_t> replaced = imu::replaceGlitches(imu, options.imu_glitch_gyro_rad_s, options.imu_glitch_accel_mps2);
  if (replaced.empty()) return;
  warnings->push_back(where + formatText(": %zu IMU reading(s) replaced as glitches, the first at t = %.3f s (dataset.imu_glitch_*)",
                                         replaced.size(), toSeconds((*imu)[replaced.front()].t_ns)));
}

std::vector<std::pair<std::size_t, std::size_t>> pairStereo(const std::vector<std::int64_t>& left,
                                                            const std::vector<std::int64_t>& right, std::int64_t tol,
                                                            std::size_t unpaired[2]) {
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  std::size_t i = 0, j = 0;
  while (i < left.size() && j < right.size()) {
    const std::int64_t d = left[i] - right[j];
    if (std::llabs(d) <= tol) {
      pairs.emplace_back(i++, j++);
    } else if (d < 0) {
      ++unpaired[0];
      ++i;
    } else {
      ++unpaired[1];
      ++j;
    }
  }
  unpaired[0] += left.size() - i;
  unpaired[1] += right.size() - j;
  return pairs;
}

std::optional<StereoImages> EurocDataset::loadStereo(std::size_t i) {
  const StereoRecord& rec = pairs_.at(i);
  std::optional<cv::Mat> left = loadImage(0, rec.left);
  std::optional<cv::Mat> right = loadImage(1, rec.right);
  if (!left || !right) return std::nullopt;
  return StereoImages{rec.t_ns, std::move(*left), std::move(*right)};
}

}  // namespace edgevio::io
