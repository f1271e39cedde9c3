#pragma once
// Rendered stereo frames at chosen body poses, for front-end tests: the
// simulator's scene and renderer, the EuRoC rig, rectification. Noise is on
// (read noise σ = 2 DN), as in real images.
#include <memory>

#include "edgevio/camera/stereo_rectifier.h"
#include "edgevio/io/calibration_io.h"
#include "edgevio/io/trajectory_io.h"
#include "edgevio/sim/renderer.h"
#include "edgevio/sim/scene.h"
#include "edgevio/tracking/edge_tracker.h"

namespace edgevio::test {

class RenderFixture {
 public:
  /// A room around the given scenario's path, with walls at roughly 1-4 m.
  explicit RenderFixture(const std::string& scenario = "figure8", double seconds = 14.0);
  const camera::StereoRig& rig() const { return rig_; }
  const camera::StereoRectifier& rectifier() const { return *rect_; }
  const io::Trajectory& path() const { return samples_; }  ///< 200 Hz
  /// Rectified full-resolution stereo pair seen from body pose T_w_b.
  tracking::StereoFrame frame(const geometry::SE3& T_w_b, std::int64_t t_ns = 0, std::uint64_t noise_key = 1) const;
  /// Ray-cast z-depth [m] of the rectified left camera at full resolution.
  cv::Mat rectifiedDepth(const geometry::SE3& T_w_b) const;

 private:
  camera::StereoRig rig_;
  io::Trajectory samples_;
  sim::Scene scene_;
  std::unique_ptr<camera::StereoRectifier> rect_;
  std::unique_ptr<sim::RayTable> rays_[2];
};

}  // namespace edgevio::test
