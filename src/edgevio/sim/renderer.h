#pragma once
// Per-pixel ray casting of a Scene through a calibrated camera, lens distortion
// included (issue #4). Each pixel's viewing ray comes from CameraModel::unproject,
// computed once per camera (RayTable); a frame only rotates the rays into the
// world. Texture aliasing is avoided by trilinear mip-mapping with the pixel's
// footprint on the surface: footprint ≈ t · Δθ / |cos(incidence)|, with Δθ the
// angle between neighbouring rays.
#include <opencv2/core.hpp>

#include <vector>

#include "edgevio/camera/camera_model.h"
#include "edgevio/geometry/se3.h"
#include "edgevio/sim/scene.h"

namespace edgevio::sim {

class RayTable {
 public:
  explicit RayTable(const camera::CameraModel& camera);
  int width() const { return width_; }
  int height() const { return height_; }
  /// Unit ray of pixel (u, v) in the camera frame, and its angular size [rad].
  const Eigen::Vector3f& ray(int u, int v) const { return rays_[static_cast<std::size_t>(v * width_ + u)]; }
  float pixelAngle(int u, int v) const { return angle_[static_cast<std::size_t>(v * width_ + u)]; }

 private:
  int width_, height_;
  std::vector<Eigen::Vector3f> rays_;
  std::vector<float> angle_;
};

struct RenderOptions {
  int threads = 2;           ///< rows are split over this many threads (output does not depend on it)
  float light_scale = 1.0f;  ///< multiplies every light (sudden lighting changes)
};

/// Renders radiance (CV_32FC1, roughly [0, 1]) and, if `depth` is non-null,
/// the depth along the camera's z axis [m] (CV_32FC1).
void render(const Scene& scene, const RayTable& rays, const geometry::SE3& T_w_c, const RenderOptions& options,
            cv::Mat* radiance, cv::Mat* depth = nullptr);

}  // namespace edgevio::sim
