#include "edgevio/sim/renderer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <thread>

namespace edgevio::sim {

using Vec3f = Eigen::Vector3f;

RayTable::RayTable(const camera::CameraModel& camera) : width_(camera.width), height_(camera.height) {
  rays_.resize(static_cast<std::size_t>(width_ * height_));
  angle_.resize(rays_.size());
  for (int v = 0; v < height_; ++v)
    for (int u = 0; u < width_; ++u) rays_[static_cast<std::size_t>(v * width_ + u)] = camera.unproject(Vec2(u, v)).cast<float>();
  for (int v = 0; v < height_; ++v)
    for (int u = 0; u < width_; ++u) {
      const int un = u + 1 < width_ ? u + 1 : u - 1, vn = v + 1 < height_ ? v + 1 : v - 1;
      const Vec3f& r = ray(u, v);
      const float a = std::max((r - ray(un, v)).norm(), (r - ray(u, vn)).norm());
      angle_[static_cast<std::size_t>(v * width_ + u)] = a;
    }
}

namespace {

struct Hit {
  float t = std::numeric_limits<float>::infinity();
  int face = 0;                   // 2·axis + side
  const SceneBox* box = nullptr;  // the room or an obstacle
};

/// The nearest surface along o + t·d: the room's exit face, or the nearest
/// obstacle among `candidates` (slab test).
inline Hit intersect(const Scene& s, const std::vector<const SceneBox*>& candidates, const Vec3f& o, const Vec3f& d,
                     const Vec3f& inv) {
  Hit h;
  h.box = &s.room;
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0.0f) continue;
    const bool high = d[a] > 0.0f;
    const float t = ((high ? s.room.hi[a] : s.room.lo[a]) - o[a]) * inv[a];
    if (t < h.t) {
      h.t = t;
      h.face = 2 * a + (high ? 1 : 0);
    }
  }
  for (const SceneBox* b : candidates) {
    float tmin = 0.0f, tmax = h.t;
    int axis = -1;
    for (int a = 0; a < 3; ++a) {
      float t0 = (b->lo[a] - o[a]) * inv[a], t1 = (b->hi[a] - o[a]) * inv[a];
      if (t0 > t1) std::swap(t0, t1);
      if (t0 > tmin) {
        tmin = t0;
        axis = a;
      }
      tmax = std::min(tmax, t1);
      if (tmin > tmax) break;
    }
    if (tmin <= tmax && axis >= 0 && tmin < h.t) {
      h.t = tmin;
      h.face = 2 * axis + (d[axis] > 0.0f ? 0 : 1);
      h.box = b;
    }
  }
  return h;
}

constexpr int kTile = 16;

/// Obstacles that may be hit by any ray of the tile: the tile's rays lie in a
/// cone around its centre ray; an obstacle's bounding sphere must meet it.
std::vector<const SceneBox*> tileCandidates(const Scene& s, const RayTable& rays, const Eigen::Matrix3f& R,
                                            const Vec3f& o, int u0, int v0, int u1, int v1) {
  const Vec3f axis = (R * rays.ray((u0 + u1 - 1) / 2, (v0 + v1 - 1) / 2)).normalized();
  float cos_half = 1.0f;
  for (int u : {u0, u1 - 1})
    for (int v : {v0, v1 - 1}) cos_half = std::min(cos_half, axis.dot((R * rays.ray(u, v)).normalized()));
  const float half = std::acos(std::clamp(cos_half, -1.0f, 1.0f)) + 0.02f;  // margin: distortion bends tile edges
  std::vector<const SceneBox*> out;
  for (const SceneBox& b : s.obstacles) {
    const Vec3f c = 0.5f * (b.lo + b.hi) - o;
    const float r = 0.5f * (b.hi - b.lo).norm();
    const float dist = c.norm();
    if (dist <= r) {
      out.push_back(&b);
      continue;
    }
    const float angle = std::acos(std::clamp(axis.dot(c) / dist, -1.0f, 1.0f));
    if (angle <= half + std::asin(r / dist)) out.push_back(&b);
  }
  return out;
}

void renderTiles(const Scene& s, const RayTable& rays, const Eigen::Matrix3f& R, const Vec3f& o, float light_scale,
                 int tile_row0, int tile_row1, cv::Mat* radiance, cv::Mat* depth) {
  const int W = rays.width(), H = rays.height();
  for (int tr = tile_row0; tr < tile_row1; ++tr) {
    const int v0 = tr * kTile, v1 = std::min(v0 + kTile, H);
    for (int u0 = 0; u0 < W; u0 += kTile) {
      const int u1 = std::min(u0 + kTile, W);
      const std::vector<const SceneBox*> candidates = tileCandidates(s, rays, R, o, u0, v0, u1, v1);
      for (int v = v0; v < v1; ++v) {
        float* out = radiance->ptr<float>(v);
        float* dep = depth ? depth->ptr<float>(v) : nullptr;
        for (int u = u0; u < u1; ++u) {
          const Vec3f& rc = rays.ray(u, v);
          const Vec3f d = R * rc;
          const Vec3f inv(1.0f / d.x(), 1.0f / d.y(), 1.0f / d.z());
          const Hit h = intersect(s, candidates, o, d, inv);
          const Vec3f x = o + h.t * d;
          const int axis = h.face / 2;
          const auto face = static_cast<std::size_t>(h.face);
          const SurfaceMaterial& m = s.materials[static_cast<std::size_t>(h.box->material[face])];
          float su, sv;
          faceCoordinates(axis, x, &su, &sv);
          const float footprint = h.t * rays.pixelAngle(u, v) / std::max(std::abs(d[axis]), 0.15f);
          const float albedo = m.albedo * s.textures[static_cast<std::size_t>(m.texture)].sample(su + m.u_offset, sv + m.v_offset, footprint);
          const float light = s.ambient + light_scale * (h.box->light[face].sample(su, sv) - s.ambient);
          out[u] = albedo * light;
          if (dep) dep[u] = h.t * rc.z();
        }
      }
    }
  }
}

}  // namespace

void render(const Scene& scene, const RayTable& rays, const geometry::SE3& T_w_c, const RenderOptions& options,
            cv::Mat* radiance, cv::Mat* depth) {
  radiance->create(rays.height(), rays.width(), CV_32FC1);
  if (depth) depth->create(rays.height(), rays.width(), CV_32FC1);
  const Eigen::Matrix3f R = T_w_c.rotationMatrix().cast<float>();
  const Vec3f o = T_w_c.translation().cast<float>();
  const int threads = std::clamp(options.threads, 1, 64);
  const int tile_rows = (rays.height() + kTile - 1) / kTile;
  std::vector<std::thread> pool;
  for (int k = 1; k < threads; ++k)
    pool.emplace_back(renderTiles, std::cref(scene), std::cref(rays), std::cref(R), std::cref(o), options.light_scale,
                      tile_rows * k / threads, tile_rows * (k + 1) / threads, radiance, depth);
  renderTiles(scene, rays, R, o, options.light_scale, 0, tile_rows / threads, radiance, depth);
  for (auto& t : pool) t.join();
}

}  // namespace edgevio::sim
