#include "common/render_fixture.h"

#include "edgevio/sim/sensor_model.h"
#include "edgevio/sim/trajectory_source.h"

namespace edgevio::test {

RenderFixture::RenderFixture(const std::string& scenario, double seconds) : rig_(io::eurocDefaultRig()) {
  samples_ = sim::scenarioSamples(scenario, seconds, 1.0, rig_.T_b_c[0]);
  std::vector<Vec3> path;
  for (const auto& s : samples_) path.push_back(s.T_w_b.translation());
  sim::SceneOptions o;
  o.room_margin_m = 1.8;
  o.min_room_size_m = 5.0;
  o.texture_log2_size = 9;
  scene_ = sim::buildScene(path, o, 21);
  rect_ = std::make_unique<camera::StereoRectifier>(rig_, camera::RectificationOptions{});
  for (int c = 0; c < 2; ++c) rays_[c] = std::make_unique<sim::RayTable>(rig_.cam[c]);
}

tracking::StereoFrame RenderFixture::frame(const geometry::SE3& T_w_b, std::int64_t t_ns, std::uint64_t noise_key) const {
  cv::Mat raw[2], radiance;
  sim::SensorEffects fx;
  fx.gain = 0.7;
  fx.noise_sigma = 2.0;
  fx.vignetting = 0.2;
  for (int c = 0; c < 2; ++c) {
    sim::render(scene_, *rays_[c], T_w_b * rig_.T_b_c[c], sim::RenderOptions{}, &radiance);
    raw[c] = sim::sensorImage(radiance, rig_.cam[c], fx, noise_key * 2 + static_cast<std::uint64_t>(c));
  }
  tracking::StereoFrame f;
  f.t_ns = t_ns;
  rect_->rectify(raw[0], raw[1], &f.left, &f.right);
  return f;
}

cv::Mat RenderFixture::rectifiedDepth(const geometry::SE3& T_w_b) const {
  const sim::RayTable rays(rect_->rectifiedCamera());
  cv::Mat radiance, depth;
  sim::render(scene_, rays, T_w_b * rect_->T_b_rect(0), sim::RenderOptions{}, &radiance, &depth);
  return depth;
}

}  // namespace edgevio::test
