#pragma once
// Procedural, seamlessly tiling surface textures with mip levels (issue #4:
// "rich, natural-looking texture at several scales"). Each texture is a square
// grey-level albedo image in [0, 1] covering `size_m` metres; the mip chain
// (box-filtered halvings) lets the renderer anti-alias by sampling at the level
// that matches the pixel footprint (trilinear filtering).
#include <cstdint>
#include <cstring>
#include <string>
#include <algorithm>
#include <vector>

namespace edgevio::sim {

namespace texture_detail {
/// Index of texel (x, y) in a level of size s stored in 8x8 blocks (row-major below 8).
inline std::size_t blockIndex(int s, int x, int y) {
  if (s < 8) return static_cast<std::size_t>(y * s + x);
  return static_cast<std::size_t>((((y >> 3) * (s >> 3) + (x >> 3)) << 6) + ((y & 7) << 3) + (x & 7));
}
// Baseline x86-64 has no SSE4.1 round instruction, so std::floor and std::log2
// are library calls; these inline versions keep texture sampling cheap.
inline float fastFloor(float x) {
  const float t = static_cast<float>(static_cast<int>(x));
  return t > x ? t - 1.0f : t;
}
/// log2 for x >= 1, exact at powers of two, linear in between (enough for
/// choosing and blending mip levels).
inline float fastLog2(float x) {
  std::uint32_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  const int e = static_cast<int>((bits >> 23) & 0xFFu) - 127;  // x = 1.f · 2^e
  bits = (bits & 0x007FFFFFu) | 0x3F800000u;
  float m;  // 1.f in [1, 2)
  std::memcpy(&m, &bits, sizeof m);
  return static_cast<float>(e) + (m - 1.0f);
}
}  // namespace texture_detail

enum class TextureKind { kBricks, kPosterWall, kWoodPlanks, kFloorTiles, kCeilingPanels, kStripes, kConcrete, kShapes };
constexpr int kTextureKinds = 8;

class Texture {
 public:
  /// Generates a texture of 2^log2_size texels square covering size_m metres.
  Texture(TextureKind kind, int log2_size, double size_m, std::uint64_t seed);
  /// Loads a user image (any size; resized to a power of two) covering size_m metres.
  static Texture fromImage(const std::string& path, double size_m);

  /// Albedo at surface coordinates (u, v) [m] for a footprint of `footprint_m`
  /// metres per pixel; wraps around (tiles). Inline: called once per pixel.
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

inline float Texture::bilinear(int level, float x, float y) const {
  using namespace texture_detail;
  const int s = size_ >> level;
  const std::vector<std::uint8_t>& img = levels_[static_cast<std::size_t>(level)];
  x -= 0.5f;
  y -= 0.5f;
  const float fx = fastFloor(x), fy = fastFloor(y);
  const float tx = x - fx, ty = y - fy;
  const int mask = s - 1;  // power-of-two sizes: wrap with a mask
  const int x0 = static_cast<int>(fx) & mask, y0 = static_cast<int>(fy) & mask;
  const int x1 = (x0 + 1) & mask, y1 = (y0 + 1) & mask;
  const float a = img[blockIndex(s, x0, y0)], b = img[blockIndex(s, x1, y0)];
  const float c = img[blockIndex(s, x0, y1)], d = img[blockIndex(s, x1, y1)];
  return ((a + tx * (b - a)) + ty * ((c + tx * (d - c)) - (a + tx * (b - a)))) * (1.0f / 255.0f);
}

inline float Texture::sample(float u_m, float v_m, float footprint_m) const {
  using namespace texture_detail;
  const float fp = footprint_m * texels_per_m_;  // texels per pixel
  const float lod = fp > 1.0f ? fastLog2(fp) : 0.0f;
  const int max_level = static_cast<int>(levels_.size()) - 1;
  int l0 = std::min(static_cast<int>(lod), max_level);
  float w = std::min(lod - static_cast<float>(l0), 1.0f);
  // A blend weight within 1/16 of 0 or 1 is invisible after 8-bit output:
  // sample one level only (saves a third of the texture time).
  if (w > 15.0f / 16.0f && l0 < max_level) {
    ++l0;
    w = 0.0f;
  }
  const int l1 = std::min(l0 + 1, max_level);
  // Wrap the coordinates to one tile first: keeps float precision at any distance.
  const float tu = u_m * texels_per_m_, tv = v_m * texels_per_m_;
  const float n = static_cast<float>(size_), inv_n = 1.0f / n;
  const float x = tu - fastFloor(tu * inv_n) * n, y = tv - fastFloor(tv * inv_n) * n;
  const float s0 = 1.0f / static_cast<float>(1 << l0);
  const float a = bilinear(l0, x * s0, y * s0);
  if (w < 1.0f / 16.0f || l1 == l0) return a;
  const float b = bilinear(l1, x * s0 * 0.5f, y * s0 * 0.5f);
  return a + w * (b - a);
}

}  // namespace edgevio::sim
