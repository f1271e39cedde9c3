#pragma once
// Shared by the front-end benchmarks: rendered, rectified EuRoC-rig frames
// along the figure8 scenario in a textured room (walls at roughly 1-4 m).
#include <memory>

#include "edgevio/camera/stereo_rectifier.h"
#include "edgevio/io/calibration_io.h"
#include "edgevio/sim/stereo_frame_renderer.h"
#include "edgevio/sim/trajectory_source.h"

namespace edgevio::bench {

struct FrontendFixture {
  camera::StereoRig rig = io::eurocDefaultRig();
  io::Trajectory path = sim::scenarioSamples("figure8", 14.0, 1.0, rig.T_b_c[0]);
  sim::Scene scene;
  std::unique_ptr<sim::StereoFrameRenderer> renderer;
  std::unique_ptr<camera::StereoRectifier> rect;

  FrontendFixture() {
    std::vector<Vec3> pts;
    for (const auto& s : path) pts.push_back(s.T_w_b.translation());
    sim::SceneOptions o;
    o.room_margin_m = 1.8;
    o.min_room_size_m = 5.0;
    scene = sim::buildScene(pts, o, 21);
    renderer = std::make_unique<sim::StereoFrameRenderer>(scene, rig);
    rect = std::make_unique<camera::StereoRectifier>(rig, camera::RectificationOptions{});
  }
  /// Rectified full-resolution pair at path sample i (200 Hz).
  void frame(std::size_t i, cv::Mat* left, cv::Mat* right) const {
    cv::Mat raw[2];
    renderer->render(path[i].T_w_b, {0.7, 0.2, 2.0}, i, &raw[0], &raw[1]);
    rect->rectify(raw[0], raw[1], left, right);
  }
  /// T_nr between samples i (reference) and j, in rectified-camera coordinates.
  geometry::SE3 relative(std::size_t i, std::size_t j) const {
    const geometry::SE3 T_b_c = rect->T_b_rect(0);
    return (path[j].T_w_b * T_b_c).inverse() * (path[i].T_w_b * T_b_c);
  }
};

}  // namespace edgevio::bench
