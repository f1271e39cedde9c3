#include "common/render_fixture.h"

#include "edgevio/io/calibration_io.h"
#include "edgevio/sim/renderer.h"
#include "edgevio/sim/trajectory_source.h"
#include "edgevio/vision/keyframe_depth.h"

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
  renderer_ = std::make_unique<sim::StereoFrameRenderer>(scene_, rig_);
}

std::shared_ptr<const tracking::KeyframeData> RenderFixture::keyframe(const geometry::SE3& T_w_b, std::int64_t t_ns,
                                                                      std::uint64_t noise_key) const {
  const tracking::StereoFrame f = frame(T_w_b, t_ns, noise_key);
  const vision::VisionOptions vo;
  auto k = std::make_shared<tracking::KeyframeData>();
  k->t_ns = t_ns;
  k->pyramid = vision::buildEdgePyramid(f.left, rect_->rectifiedCamera(), vo);
  k->depth = vision::computeKeyframeDepth(k->pyramid, f.right.get(), rect_->baseline(), vo);
  return k;
}

tracking::StereoFrame RenderFixture::frame(const geometry::SE3& T_w_b, std::int64_t t_ns, std::uint64_t noise_key) const {
  cv::Mat raw[2];
  renderer_->render(T_w_b, {0.7, 0.2, 2.0}, noise_key, &raw[0], &raw[1]);
  tracking::StereoFrame f;
  f.t_ns = t_ns;
  f.left = rect_->rectify(0, raw[0]);
  f.right = rect_->rectify(1, raw[1]);
  return f;
}

cv::Mat RenderFixture::rectifiedDepth(const geometry::SE3& T_w_b) const {
  const sim::RayTable rays(rect_->rectifiedCamera());
  cv::Mat radiance, depth;
  sim::render(scene_, rays, T_w_b * rect_->T_b_rect(0), sim::RenderOptions{}, &radiance, &depth);
  return depth;
}

}  // namespace edgevio::test
