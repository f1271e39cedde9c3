#include "edgevio/sim/stereo_frame_renderer.h"

namespace edgevio::sim {

StereoFrameRenderer::StereoFrameRenderer(const Scene& scene, const camera::StereoRig& rig) : scene_(scene), rig_(rig) {
  for (int c = 0; c < 2; ++c) rays_[c] = std::make_unique<RayTable>(rig_.cam[c]);
}

void StereoFrameRenderer::render(const geometry::SE3& T_w_b, const SensorEffects& effects, std::uint64_t noise_key,
                                 cv::Mat* left, cv::Mat* right) const {
  cv::Mat radiance;
  cv::Mat* out[2] = {left, right};
  for (int c = 0; c < 2; ++c) {
    sim::render(scene_, *rays_[c], T_w_b * rig_.T_b_c[c], RenderOptions{}, &radiance);
    *out[c] = sensorImage(radiance, rig_.cam[c], effects, noise_key * 2 + static_cast<std::uint64_t>(c));
  }
}

cv::Mat StereoFrameRenderer::depth(const camera::CameraModel& camera, const geometry::SE3& T_w_c) const {
  const RayTable rays(camera);
  cv::Mat radiance, z;
  sim::render(scene_, rays, T_w_c, RenderOptions{}, &radiance, &z);
  return z;
}

}  // namespace edgevio::sim
