#pragma once
// Procedural, seamlessly tiling surface textures with mip levels (issue #4:
// "rich, natural-looking texture at several scales"). Each texture is a square
// grey-level albedo image in [0, 1] covering `size_m` metres; the mip chain
// (box-filtered halvings) lets the renderer anti-alias by sampling at the level
// that matches the pixel footprint (trilinear filtering).
#include <cstdint>
#include <string>
#include <vector>

namespace edgevio::sim {

enum class TextureKind { kBricks, kPosterWall, kWoodPlanks, kFloorTiles, kCeilingPanels, kStripes, kConcrete, kShapes };
constexpr int kTextureKinds = 8;

class Texture {
 public:
  /// Generates a texture of 2^log2_size texels square covering size_m metres.
  Texture(TextureKind kind, int log2_size, double size_m, std::uint64_t seed);
  /// Loads a user image (any size; resized to a power of two) covering size_m metres.
  static Texture fromImage(const std::string& path, double size_m);

  /// Albedo at surface coordinates (u, v) [m] for a footprint of `footprint_m`
  /// metres per pixel; wraps around (tiles).
  float sample(float u_m, float v_m, float footprint_m) const;
  int size() const { return size_; }
  /// Albedo of texel (x, y) of level 0, in [0, 1] (for tests and inspection).
  float texel(int x, int y) const;

 private:
  Texture() = default;
  /// Stores level 0 (row-major, [0, 1]) and its mip chain.
  void setLevels(const std::vector<float>& level0);
  float bilinear(int level, float x, float y) const;

  int size_ = 0;
  float texels_per_m_ = 1.0f;
  // 8-bit texels in 8x8 blocks (one 64-byte cache line each), so the four
  // texels of a bilinear fetch rarely span more than two lines.
  std::vector<std::vector<std::uint8_t>> levels_;
};

}  // namespace edgevio::sim
