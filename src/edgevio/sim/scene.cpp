#include "edgevio/sim/scene.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "edgevio/common/error.h"
#include "edgevio/sim/random.h"

namespace edgevio::sim {

namespace {

constexpr float kLightCell = 0.1f;  // [m]

/// Bakes ambient + Lambertian point lights with 1/(1 + d²/16) falloff on every face of a box.
void bakeLighting(SceneBox* box, bool inward, const std::vector<PointLight>& lights, float ambient) {
  for (int f = 0; f < 6; ++f) {
    const int axis = f / 2;
    const bool high = f % 2 == 1;
    Eigen::Vector3f n = Eigen::Vector3f::Zero();
    n[axis] = inward ? (high ? -1.0f : 1.0f) : (high ? 1.0f : -1.0f);
    const float plane = high ? box->hi[axis] : box->lo[axis];
    const int ua = axis == 0 ? 1 : 0, va = axis == 2 ? 1 : 2;
    LightMap& m = box->light[static_cast<std::size_t>(f)];
    m.u0 = box->lo[ua];
    m.v0 = box->lo[va];
    m.inv_cell = 1.0f / kLightCell;
    m.nu = static_cast<int>(std::ceil((box->hi[ua] - box->lo[ua]) / kLightCell)) + 1;
    m.nv = static_cast<int>(std::ceil((box->hi[va] - box->lo[va]) / kLightCell)) + 1;
    m.value.resize(static_cast<std::size_t>(m.nu * m.nv));
    for (int j = 0; j < m.nv; ++j)
      for (int i = 0; i < m.nu; ++i) {
        Eigen::Vector3f x;
        x[axis] = plane;
        x[ua] = m.u0 + static_cast<float>(i) * kLightCell;
        x[va] = m.v0 + static_cast<float>(j) * kLightCell;
        float e = ambient;
        for (const PointLight& l : lights) {
          Eigen::Vector3f L = l.position - x;
          const float d2 = L.squaredNorm();
          L /= std::sqrt(d2);
          e += l.intensity * std::max(0.0f, n.dot(L)) / (1.0f + d2 / 16.0f);
        }
        m.value[static_cast<std::size_t>(j * m.nu + i)] = e;
      }
  }
}

}  // namespace

double distanceToBox(const SceneBox& box, const Vec3& p) {
  const Vec3 lo = box.lo.cast<double>(), hi = box.hi.cast<double>();
  return (lo - p).cwiseMax(p - hi).cwiseMax(0.0).norm();
}

Scene buildScene(const std::vector<Vec3>& path, const SceneOptions& o, std::uint64_t seed) {
  if (path.empty()) throw InputError("scene: empty path");
  Vec3 lo = path.front(), hi = path.front();
  for (const Vec3& p : path) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Vec3 extent = hi - lo;
  if (extent.maxCoeff() + 2 * o.room_margin_m > o.max_room_size_m)
    throw InputError("scene: the path spans " + std::to_string(extent.x()) + " x " + std::to_string(extent.y()) +
                     " x " + std::to_string(extent.z()) + " m; with margins the room would exceed sim.max_room_size_m = " +
                     std::to_string(o.max_room_size_m) + " m (simulate a shorter span with --start/--duration)");
  Rng rng(hashCombine(seed, 0x5ce9e));
  Scene s;
  Vec3 room_lo = lo - Vec3(o.room_margin_m, o.room_margin_m, o.floor_below_path_m);
  Vec3 room_hi = hi + Vec3(o.room_margin_m, o.room_margin_m, o.ceiling_above_path_m);
  for (int a = 0; a < 2; ++a) {
    const double grow = o.min_room_size_m - (room_hi[a] - room_lo[a]);
    if (grow > 0) {
      room_lo[a] -= grow / 2;
      room_hi[a] += grow / 2;
    }
  }
  s.room.lo = room_lo.cast<float>();
  s.room.hi = room_hi.cast<float>();

  // Textures: every procedural kind, plus the user's images if given.
  for (int k = 0; k < kTextureKinds; ++k)
    s.textures.emplace_back(static_cast<TextureKind>(k), o.texture_log2_size, o.texture_tile_m, hashCombine(seed, static_cast<std::uint64_t>(k)));
  std::vector<int> wall_textures = {static_cast<int>(TextureKind::kBricks), static_cast<int>(TextureKind::kPosterWall),
                                    static_cast<int>(TextureKind::kConcrete), static_cast<int>(TextureKind::kStripes),
                                    static_cast<int>(TextureKind::kShapes)};
  if (!o.texture_dir.empty()) {
    std::vector<std::string> files;
    for (const auto& e : std::filesystem::directory_iterator(o.texture_dir)) {
      const std::string ext = e.path().extension().string();
      if (ext == ".png" || ext == ".jpg" || ext == ".jpeg") files.push_back(e.path().string());
    }
    std::sort(files.begin(), files.end());
    if (files.empty()) throw InputError(o.texture_dir, 0, "no .png/.jpg texture images in this folder");
    wall_textures.clear();
    for (const auto& f : files) {
      wall_textures.push_back(static_cast<int>(s.textures.size()));
      s.textures.push_back(Texture::fromImage(f, o.texture_tile_m));
    }
  }
  const auto material = [&](int texture, double lo_albedo, double hi_albedo) {
    s.materials.push_back({texture, static_cast<float>(rng.uniform(lo_albedo, hi_albedo)),
                           static_cast<float>(rng.uniform(0, o.texture_tile_m)), static_cast<float>(rng.uniform(0, o.texture_tile_m))});
    return static_cast<int>(s.materials.size()) - 1;
  };
  const int floor_tex = rng.uniform() < 0.5 ? static_cast<int>(TextureKind::kWoodPlanks) : static_cast<int>(TextureKind::kFloorTiles);
  s.room.material[4] = material(floor_tex, 0.8, 1.1);
  s.room.material[5] = material(static_cast<int>(TextureKind::kCeilingPanels), 0.9, 1.1);
  for (int f = 0; f < 4; ++f)
    s.room.material[static_cast<std::size_t>(f)] = material(wall_textures[static_cast<std::size_t>(rng.integer(0, static_cast<int>(wall_textures.size()) - 1))], 0.8, 1.15);

  // Obstacles: random boxes, panels and pillars, rejected when too close to the path.
  const Vec3 rlo = room_lo, rhi = room_hi;
  for (int placed = 0, attempt = 0; placed < o.obstacle_count && attempt < 400; ++attempt) {
    SceneBox b;
    const int type = rng.integer(0, 2);
    Vec3 size;
    double z0 = rlo.z();
    if (type == 0) {  // box on the floor
      size = Vec3(rng.uniform(0.4, 1.4), rng.uniform(0.4, 1.4), rng.uniform(0.4, 1.6));
    } else if (type == 1) {  // panel, standing or hanging, oriented along x or y
      const double w = rng.uniform(1.0, 2.5), t = 0.06;
      size = rng.uniform() < 0.5 ? Vec3(w, t, rng.uniform(1.0, 2.2)) : Vec3(t, w, rng.uniform(1.0, 2.2));
      if (rng.uniform() < 0.3) z0 = rhi.z() - size.z() - 0.1;
    } else {  // pillar, floor to ceiling
      const double w = rng.uniform(0.3, 0.7);
      size = Vec3(w, w, rhi.z() - rlo.z());
    }
    const Vec3 corner(rng.uniform(rlo.x() + 0.05, rhi.x() - size.x() - 0.05), rng.uniform(rlo.y() + 0.05, rhi.y() - size.y() - 0.05), z0);
    b.lo = corner.cast<float>();
    b.hi = (corner + size).cast<float>();
    bool clear = true;
    for (const Vec3& p : path) clear = clear && distanceToBox(b, p) >= o.obstacle_clearance_m;
    if (!clear) continue;
    const int tex = rng.integer(0, kTextureKinds - 1);
    const int mat = material(tex, 0.6, 1.2);
    for (auto& m : b.material) m = mat;
    b.material[5] = material(tex, 0.9, 1.3);  // top faces lit differently
    s.obstacles.push_back(b);
    ++placed;
  }

  // Lights: a grid under the ceiling, one per ~16 m² of floor.
  const int nx = std::max(1, static_cast<int>(std::round((rhi.x() - rlo.x()) / 4.0)));
  const int ny = std::max(1, static_cast<int>(std::round((rhi.y() - rlo.y()) / 4.0)));
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j)
      s.lights.push_back({Eigen::Vector3f(static_cast<float>(rlo.x() + (i + 0.5) * (rhi.x() - rlo.x()) / nx),
                                          static_cast<float>(rlo.y() + (j + 0.5) * (rhi.y() - rlo.y()) / ny),
                                          static_cast<float>(rhi.z() - 0.3)),
                          static_cast<float>(rng.uniform(0.7, 1.0))});
  bakeLighting(&s.room, true, s.lights, s.ambient);
  for (auto& b : s.obstacles) bakeLighting(&b, false, s.lights, s.ambient);
  return s;
}

}  // namespace edgevio::sim
