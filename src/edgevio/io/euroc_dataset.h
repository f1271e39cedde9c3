#pragma once
// Reader of EuRoC ASL folders (also the TUM-VI "euroc" export):
//   mav0/cam{0,1}/data.csv + data/*.png + sensor.yaml, mav0/imu0/data.csv +
//   sensor.yaml, optional mav0/state_groundtruth_estimate0/data.csv.
// Opening reads the CSV indexes, IMU and ground truth; images are decoded one
// stereo pair at a time (loadStereo), so a sequence is never held in memory.
//
// Outcomes for bad input (issue #2):
//  - image row whose file is missing or does not decode, or whose timestamp
//    repeats or goes back (a driver's clock glitch): skipped, counted, one warning;
//  - frames without a partner in the other camera: skipped, counted;
//  - malformed rows, NaN/inf, duplicate or decreasing IMU timestamps, an image
//    whose size differs from the calibration: InputError naming file and line;
//  - IMU gaps longer than DatasetOptions::imu_gap_warning_s: a warning.
#include <opencv2/core.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "edgevio/camera/calibration.h"
#include "edgevio/imu/imu_types.h"
#include "edgevio/io/dataset_options.h"
#include "edgevio/io/sequence.h"
#include "edgevio/io/trajectory_io.h"

namespace edgevio::io {

struct ImageRecord {
  std::int64_t t_ns = 0;
  std::string path;       ///< absolute or dataset-relative image path
  std::size_t line = 0;   ///< line in data.csv (for messages)
};

struct StereoRecord {
  std::int64_t t_ns = 0;  ///< timestamp of the left image
  ImageRecord left, right;
};

/// A decoded stereo pair (raw, not yet rectified), 8-bit single channel.
struct StereoImages {
  std::int64_t t_ns = 0;
  cv::Mat left, right;
};

class EurocDataset final : public Sequence {
 public:
  /// `root` is the folder that holds mav0/ (or mav0 itself). Throws InputError.
  EurocDataset(const std::string& root, const DatasetOptions& options);

  // Sequence
  std::string name() const override;
  std::string location() const override;
  std::size_t frameCount() const override { return pairs_.size(); }
  std::int64_t frameTime(std::size_t i) const override { return pairs_.at(i).t_ns; }
  std::optional<cv::Mat> leftImage(std::size_t i) override { return loadImage(i, 0); }
  std::function<cv::Mat()> rightImageLoader(std::size_t i) const override;
  std::size_t unreadableImages() const override { return unreadable_[0] + unreadable_[1]; }
  std::size_t cameraFrames(int cam) const override { return rows_[cam] - unreadable_[cam]; }

  const std::vector<StereoRecord>& stereoPairs() const { return pairs_; }
  const std::string& mav0() const { return mav0_; }

  std::size_t cameraRows(int cam) const { return rows_[cam]; }
  /// Rows whose image file is missing or failed to decode.
  std::size_t unreadableImages(int cam) const { return unreadable_[cam]; }
  /// Readable frames with no partner in the other camera.
  std::size_t unpairedFrames(int cam) const { return unpaired_[cam]; }
  double imuRateHz() const;
  /// Time from the first to the last stereo pair [s].
  double durationSeconds() const;

  /// Decodes pair i. Returns nullopt (counted, with a warning) when an image
  /// fails to decode; throws InputError when its size differs from the calibration.
  std::optional<StereoImages> loadStereo(std::size_t i);
  /// Decodes camera `cam`'s image of pair i, as loadStereo does.
  std::optional<cv::Mat> loadImage(std::size_t i, int cam);

 private:
  std::vector<ImageRecord> readImageList(int cam);
  void readImu();
  void pairFrames(const std::vector<ImageRecord>& left, const std::vector<ImageRecord>& right);
  std::optional<cv::Mat> loadImage(int cam, const ImageRecord& rec);

  DatasetOptions options_;
  std::string mav0_;
  std::vector<StereoRecord> pairs_;
  std::size_t rows_[2] = {0, 0};
  std::size_t unreadable_[2] = {0, 0};
  std::size_t unpaired_[2] = {0, 0};
};

/// Decodes an 8-bit grey image; empty when the file is missing or does not
/// decode. No side effects, so any thread may call it.
cv::Mat decodeGrayImage(const std::string& path);

}  // namespace edgevio::io
