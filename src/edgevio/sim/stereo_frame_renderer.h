#pragma once
// Renders raw stereo pairs of a rig at chosen body poses: the simulator's
// camera path without the sequence around it. Used by tests and benchmarks of
// the front end, and by anyone who wants single views of a scene.
#include <opencv2/core.hpp>

#include <memory>

#include "edgevio/camera/calibration.h"
#include "edgevio/sim/renderer.h"
#include "edgevio/sim/sensor_model.h"

namespace edgevio::sim {

class StereoFrameRenderer {
 public:
  StereoFrameRenderer(const Scene& scene, const camera::StereoRig& rig);
  /// Raw (distorted) 8-bit images of both cameras at body pose T_w_b.
  void render(const geometry::SE3& T_w_b, const SensorEffects& effects, std::uint64_t noise_key, cv::Mat* left,
              cv::Mat* right) const;
  /// Z-depth [m] seen by any camera model at pose T_w_c.
  cv::Mat depth(const camera::CameraModel& camera, const geometry::SE3& T_w_c) const;

 private:
  const Scene& scene_;
  camera::StereoRig rig_;
  std::unique_ptr<RayTable> rays_[2];
};

}  // namespace edgevio::sim
