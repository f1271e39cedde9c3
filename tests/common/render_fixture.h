#pragma once
// Rendered, rectified stereo frames at chosen body poses for front-end tests:
// a room around a scenario's path (walls at roughly 1-4 m), the EuRoC rig,
// read noise σ = 2 DN and vignetting as in real images.
#include <memory>

#include "edgevio/camera/stereo_rectifier.h"
#include "edgevio/io/trajectory_io.h"
#include "edgevio/sim/scene.h"
#include "edgevio/sim/stereo_frame_renderer.h"
#include "edgevio/tracking/edge_tracker.h"

namespace edgevio::test {

class RenderFixture {
 public:
  explicit RenderFixture(const std::string& scenario = "figure8", double seconds = 14.0);
  const camera::StereoRig& rig() const { return rig_; }
  const camera::StereoRectifier& rectifier() const { return *rect_; }
  const io::Trajectory& path() const { return samples_; }  ///< 200 Hz
  tracking::StereoFrame frame(const geometry::SE3& T_w_b, std::int64_t t_ns = 0, std::uint64_t noise_key = 1) const;
  /// A keyframe (edge pyramid and stereo depth, default options) rendered at T_w_b.
  std::shared_ptr<const tracking::KeyframeData> keyframe(const geometry::SE3& T_w_b, std::int64_t t_ns,
                                                         std::uint64_t noise_key) const;
  /// True depth along the rectified left camera's z axis at each of its pixels [m].
  cv::Mat rectifiedDepth(const geometry::SE3& T_w_b) const;

 private:
  camera::StereoRig rig_;
  io::Trajectory samples_;
  sim::Scene scene_;
  std::unique_ptr<camera::StereoRectifier> rect_;
  std::unique_ptr<sim::StereoFrameRenderer> renderer_;
};

}  // namespace edgevio::test
