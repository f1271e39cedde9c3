#pragma once
// The simulated world (issue #4): an indoor room (floor, walls, ceiling) sized
// from the trajectory's bounding box, axis-aligned obstacles (boxes, panels,
// pillars) kept at least `obstacle_clearance_m` from the path, procedural
// textures on every face, and a few point lights under the ceiling.
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "edgevio/common/options.h"
#include "edgevio/geometry/types.h"
#include "edgevio/sim/texture.h"

namespace edgevio::sim {

/// The room and its contents (keys of config section `sim`).
struct SceneOptions {
  double room_margin_m, floor_below_path_m, ceiling_above_path_m, min_room_size_m, max_room_size_m;
  int obstacle_count;
  double obstacle_clearance_m;
  int texture_log2_size;
  double texture_tile_m;
  std::string texture_dir;

  EDGEVIO_OPTIONS(SceneOptions)
};

// SceneOptions's keys, defaults, units, meanings and valid values: its table in sim_options.cpp.

/// A material: which texture, its brightness and where the tile starts on the face.
struct SurfaceMaterial {
  int texture = 0;
  float albedo = 1.0f;
  float u_offset = 0.0f, v_offset = 0.0f;
};

/// Irradiance baked on a face at a fixed cell size (lighting is static, so it
/// is computed once per scene instead of per pixel), sampled bilinearly.
struct LightMap {
  float u0 = 0.0f, v0 = 0.0f, inv_cell = 10.0f;  ///< face coordinates of cell (0,0) [m], 1/cell size [1/m]
  int nu = 1, nv = 1;
  std::vector<float> value;
  float sample(float u, float v) const;
};

/// Axis-aligned box; face f = 2·axis + (0: low side, 1: high side).
struct SceneBox {
  Eigen::Vector3f lo, hi;
  std::array<int, 6> material{};
  std::array<LightMap, 6> light;
};

struct PointLight {
  Eigen::Vector3f position;
  float intensity = 1.0f;
};

struct Scene {
  SceneBox room;                   ///< seen from inside
  std::vector<SceneBox> obstacles;  ///< seen from outside
  std::vector<Texture> textures;
  std::vector<SurfaceMaterial> materials;
  std::vector<PointLight> lights;
  float ambient = 0.35f;
};

/// Builds a scene around the path (positions sampled along it). Deterministic
/// from `seed`. Throws InputError when the path is too large for a room.
Scene buildScene(const std::vector<Vec3>& path, const SceneOptions& options, std::uint64_t seed);

/// Face coordinates [m] of a point on a face with the given axis: the two other
/// world coordinates, in increasing axis order.
inline void faceCoordinates(int axis, const Eigen::Vector3f& x, float* u, float* v) {
  *u = axis == 0 ? x.y() : x.x();
  *v = axis == 2 ? x.y() : x.z();
}

/// Distance from a point to an axis-aligned box (0 inside).
double distanceToBox(const SceneBox& box, const Vec3& p);

inline float LightMap::sample(float u, float v) const {
  const float x = std::clamp((u - u0) * inv_cell, 0.0f, static_cast<float>(nu - 1));
  const float y = std::clamp((v - v0) * inv_cell, 0.0f, static_cast<float>(nv - 1));
  const int x0 = std::min(static_cast<int>(x), nu - 2 < 0 ? 0 : nu - 2), y0 = std::min(static_cast<int>(y), nv - 2 < 0 ? 0 : nv - 2);
  const int x1 = std::min(x0 + 1, nu - 1), y1 = std::min(y0 + 1, nv - 1);
  const float tx = x - static_cast<float>(x0), ty = y - static_cast<float>(y0);
  const float a = value[static_cast<std::size_t>(y0 * nu + x0)], b = value[static_cast<std::size_t>(y0 * nu + x1)];
  const float c = value[static_cast<std::size_t>(y1 * nu + x0)], d = value[static_cast<std::size_t>(y1 * nu + x1)];
  return (a + tx * (b - a)) + ty * ((c + tx * (d - c)) - (a + tx * (b - a)));
}

}  // namespace edgevio::sim
