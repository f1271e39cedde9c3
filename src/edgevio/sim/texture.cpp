#include "edgevio/sim/texture.h"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

#include "edgevio/common/error.h"
#include "edgevio/sim/random.h"

namespace edgevio::sim {

namespace {


/// Fractal periodic value noise as an n x n image in [0, 1]: octave k has a
/// (cx·2^k) x (cy·2^k) lattice of random values (wrapping, so the image tiles),
/// smoothly interpolated; amplitudes halve per octave. n and the cell counts
/// are powers of two, so indices wrap with masks.
cv::Mat fbmImage(int n, int cx, int cy, int octaves, std::uint64_t seed) {
  cv::Mat sum(n, n, CV_32FC1, cv::Scalar(0.0f));
  double amp = 0.5, norm = 0.0;
  for (int k = 0; k < octaves; ++k) {
    const int gx = std::min(cx << k, n), gy = std::min(cy << k, n);
    Rng rng(hashCombine(seed, static_cast<std::uint64_t>(k)));
    std::vector<float> g(static_cast<std::size_t>(gx * gy));
    for (auto& v : g) v = static_cast<float>(rng.uniform());
    const float sx = static_cast<float>(gx) / n, sy = static_cast<float>(gy) / n;
    for (int y = 0; y < n; ++y) {
      const float fy = (y + 0.5f) * sy - 0.5f;
      const int y0 = static_cast<int>(std::floor(fy));
      float ty = fy - static_cast<float>(y0);
      ty = ty * ty * (3 - 2 * ty);
      const float* r0 = &g[static_cast<std::size_t>(((y0 % gy + gy) % gy) * gx)];
      const float* r1 = &g[static_cast<std::size_t>((((y0 + 1) % gy + gy) % gy) * gx)];
      float* out = sum.ptr<float>(y);
      for (int x = 0; x < n; ++x) {
        const float fx = (x + 0.5f) * sx - 0.5f;
        const int x0 = static_cast<int>(std::floor(fx));
        float tx = fx - static_cast<float>(x0);
        tx = tx * tx * (3 - 2 * tx);
        const int i0 = x0 & (gx - 1), i1 = (x0 + 1) & (gx - 1);
        const float a = r0[i0] + tx * (r0[i1] - r0[i0]);
        const float b = r1[i0] + tx * (r1[i1] - r1[i0]);
        out[x] += static_cast<float>(amp) * (a + ty * (b - a));
      }
    }
    norm += amp;
    amp *= 0.5;
  }
  sum /= norm;
  return sum;
}

/// Fills img (n x n) with a shape collage: circles, rectangles, triangles, rings.
void drawShapes(cv::Mat& img, Rng& rng, int count, double min_r, double max_r) {
  const int n = img.cols;
  for (int k = 0; k < count; ++k) {
    const double tone = rng.uniform(0.05, 0.95);
    const cv::Point c(rng.integer(0, n - 1), rng.integer(0, n - 1));
    const int r = static_cast<int>(rng.uniform(min_r, max_r) * n);
    const int type = rng.integer(0, 3);
    // Draw at the position and its wrapped copies so the texture stays seamless.
    for (int dx = -n; dx <= n; dx += n) {
      for (int dy = -n; dy <= n; dy += n) {
        const cv::Point p = c + cv::Point(dx, dy);
        if (type == 0) {
          cv::circle(img, p, r, cv::Scalar(tone), cv::FILLED, cv::LINE_AA);
        } else if (type == 1) {
          cv::rectangle(img, p - cv::Point(r, r / 2), p + cv::Point(r, r / 2), cv::Scalar(tone), cv::FILLED, cv::LINE_AA);
        } else if (type == 2) {
          std::vector<cv::Point> tri = {p + cv::Point(0, -r), p + cv::Point(r, r), p + cv::Point(-r, r)};
          cv::fillConvexPoly(img, tri, cv::Scalar(tone), cv::LINE_AA);
        } else {
          cv::circle(img, p, r, cv::Scalar(tone), std::max(2, r / 4), cv::LINE_AA);
        }
      }
    }
  }
}

}  // namespace

Texture::Texture(TextureKind kind, int log2_size, double size_m, std::uint64_t seed) {
  size_ = 1 << log2_size;
  texels_per_m_ = static_cast<float>(size_ / size_m);
  const int n = size_;
  const double m = size_m;  // metres per tile
  Rng rng(hashCombine(seed, static_cast<std::uint64_t>(kind)));
  cv::Mat img(n, n, CV_32FC1);
  const cv::Mat fine_img = fbmImage(n, 16, 16, 5, rng.next());
  const cv::Mat coarse_img = fbmImage(n, 4, 4, 3, rng.next());
  const auto texel = [&](int x, int y) { return std::make_pair((x + 0.5) / n, (y + 0.5) / n); };
  // Noise lookups at texture coordinates (u, v) in [0, 1) (wrapping).
  const auto lookup = [n](const cv::Mat& noise, double u, double v) {
    const int x = static_cast<int>(std::floor(u * n)) & (n - 1), y = static_cast<int>(std::floor(v * n)) & (n - 1);
    return noise.at<float>(y, x);
  };
  const auto fine = [&](double u, double v) { return lookup(fine_img, u, v); };
  const auto coarse = [&](double u, double v) { return lookup(coarse_img, u, v); };

  switch (kind) {
    case TextureKind::kBricks: {
      // 0.24 x 0.08 m bricks with 1 cm mortar, rows offset by half a brick.
      const int rows = static_cast<int>(std::round(m / 0.08)), cols = static_cast<int>(std::round(m / 0.24));
      std::vector<float> tone(static_cast<std::size_t>(rows * cols));
      for (auto& t : tone) t = static_cast<float>(rng.uniform(0.35, 0.75));
      for (int y = 0; y < n; ++y) {
        for (int x = 0; x < n; ++x) {
          auto [u, v] = texel(x, y);
          const double fr = v * rows;
          const int r = static_cast<int>(fr);
          const double fc = u * cols + (r % 2 ? 0.5 : 0.0);
          const int c = static_cast<int>(std::floor(fc)) % cols;
          const double mortar_v = std::min(fr - r, 1 - (fr - r)) * 0.08, mortar_u = std::min(fc - std::floor(fc), std::ceil(fc) - fc) * 0.24;
          const bool mortar = mortar_v < 0.005 || mortar_u < 0.005;
          const float base = mortar ? 0.85f : tone[static_cast<std::size_t>(r * cols + c)];
          img.at<float>(y, x) = base * (0.75f + 0.5f * fine(u, v)) * (0.85f + 0.3f * coarse(u, v));
        }
      }
      break;
    }
    case TextureKind::kWoodPlanks: {
      const int planks = static_cast<int>(std::round(m / 0.16));
      std::vector<float> tone(static_cast<std::size_t>(planks));
      for (auto& t : tone) t = static_cast<float>(rng.uniform(0.3, 0.6));
      // Grain: noise stretched along the planks (fine across, coarse along).
      const cv::Mat grain = fbmImage(n, 64, 2, 3, rng.next());
      for (int y = 0; y < n; ++y) {
        for (int x = 0; x < n; ++x) {
          auto [u, v] = texel(x, y);
          const int p = static_cast<int>(u * planks);
          const double edge = std::min(u * planks - p, p + 1 - u * planks) * 0.16;
          const float g = lookup(grain, u, v + 0.37 * p);
          float val = tone[static_cast<std::size_t>(p)] * (0.6f + 0.7f * g) * (0.85f + 0.3f * fine(u, v));
          if (edge < 0.003) val *= 0.4f;
          img.at<float>(y, x) = val;
        }
      }
      break;
    }
    case TextureKind::kFloorTiles: {
      const int tiles = static_cast<int>(std::round(m / 0.4));
      std::vector<float> tone(static_cast<std::size_t>(tiles * tiles));
      for (auto& t : tone) t = static_cast<float>(rng.uniform(0.45, 0.8));
      for (int y = 0; y < n; ++y) {
        for (int x = 0; x < n; ++x) {
          auto [u, v] = texel(x, y);
          const int i = static_cast<int>(u * tiles), j = static_cast<int>(v * tiles);
          const double eu = std::min(u * tiles - i, i + 1 - u * tiles), ev = std::min(v * tiles - j, j + 1 - v * tiles);
          float val = tone[static_cast<std::size_t>(j * tiles + i)] * (0.7f + 0.6f * fine(u, v));
          if (std::min(eu, ev) * 0.4 < 0.006) val = 0.25f;
          img.at<float>(y, x) = val;
        }
      }
      break;
    }
    case TextureKind::kCeilingPanels: {
      const int panels = static_cast<int>(std::round(m / 0.6));
      for (int y = 0; y < n; ++y) {
        for (int x = 0; x < n; ++x) {
          auto [u, v] = texel(x, y);
          const double eu = std::abs(std::fmod(u * panels, 1.0) - 0.5), ev = std::abs(std::fmod(v * panels, 1.0) - 0.5);
          const float dots = fine(u * 3, v * 3) > 0.62f ? 0.6f : 1.0f;
          float val = 0.8f * dots * (0.85f + 0.2f * coarse(u, v));
          if (std::max(eu, ev) > 0.485) val = 0.3f;
          img.at<float>(y, x) = val;
        }
      }
      break;
    }
    case TextureKind::kStripes: {
      std::vector<std::pair<double, float>> bands;  // (end, tone)
      for (double pos = 0.0; pos < 1.0;) {
        pos += rng.uniform(0.004, 0.06);
        bands.emplace_back(std::min(pos, 1.0), static_cast<float>(rng.uniform(0.1, 0.9)));
      }
      for (int y = 0; y < n; ++y) {
        for (int x = 0; x < n; ++x) {
          auto [u, v] = texel(x, y);
          const double w = std::fmod(u + 0.05 * coarse(u, v), 1.0);
          float tone = bands.back().second;
          for (const auto& b : bands)
            if (w < b.first) {
              tone = b.second;
              break;
            }
          img.at<float>(y, x) = tone * (0.8f + 0.4f * fine(u, v));
        }
      }
      break;
    }
    case TextureKind::kConcrete:
    case TextureKind::kPosterWall:
    case TextureKind::kShapes: {
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
          auto [u, v] = texel(x, y);
          const float base = kind == TextureKind::kConcrete ? 0.55f : 0.7f;
          img.at<float>(y, x) = base * (0.6f + 0.5f * fine(u, v)) * (0.8f + 0.4f * coarse(u, v));
        }
      if (kind == TextureKind::kConcrete) {
        drawShapes(img, rng, 25, 0.005, 0.03);  // stains and holes
      } else if (kind == TextureKind::kShapes) {
        drawShapes(img, rng, 90, 0.01, 0.08);
      } else {
        // Posters: framed rectangles, each with its own collage.
        for (int k = 0; k < 7; ++k) {
          const int w = static_cast<int>(rng.uniform(0.1, 0.22) * n), h = static_cast<int>(rng.uniform(0.12, 0.25) * n);
          const int x0 = rng.integer(0, n - w - 1), y0 = rng.integer(0, n - h - 1);
          cv::Mat poster(h, w, CV_32FC1, cv::Scalar(rng.uniform(0.2, 0.9)));
          drawShapes(poster, rng, 12, 0.08, 0.3);
          cv::rectangle(poster, cv::Rect(0, 0, w, h), cv::Scalar(0.1), std::max(2, w / 40));
          poster.copyTo(img(cv::Rect(x0, y0, w, h)));
        }
      }
      break;
    }
  }
  cv::Mat clamped;
  cv::min(cv::max(img, 0.02), 1.0, clamped);
  setLevels(std::vector<float>(clamped.begin<float>(), clamped.end<float>()));
}

Texture Texture::fromImage(const std::string& path, double size_m) {
  const cv::Mat raw = cv::imread(path, cv::IMREAD_GRAYSCALE);
  if (raw.empty()) throw InputError(path, 0, "texture image does not exist or does not decode");
  int n = 64;
  while (n < 2048 && n < std::max(raw.cols, raw.rows)) n *= 2;
  cv::Mat resized, f;
  cv::resize(raw, resized, cv::Size(n, n), 0, 0, cv::INTER_AREA);
  resized.convertTo(f, CV_32F, 1.0 / 255.0);
  Texture t;
  t.size_ = n;
  t.texels_per_m_ = static_cast<float>(n / size_m);
  t.setLevels(std::vector<float>(f.begin<float>(), f.end<float>()));
  return t;
}


using texture_detail::blockIndex;

void Texture::setLevels(const std::vector<float>& level0) {
  std::vector<float> level = level0;
  for (int s = size_; s >= 1; s /= 2) {
    std::vector<std::uint8_t> stored(level.size());
    for (int y = 0; y < s; ++y)
      for (int x = 0; x < s; ++x)
        stored[blockIndex(s, x, y)] = static_cast<std::uint8_t>(std::clamp(level[static_cast<std::size_t>(y * s + x)] * 255.0f + 0.5f, 0.0f, 255.0f));
    levels_.push_back(std::move(stored));
    if (s == 1) break;
    // Next level: 2x2 box filter of this one (in float, before quantisation).
    const int h = s / 2;
    std::vector<float> next(static_cast<std::size_t>(h * h));
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < h; ++x) {
        const std::size_t i = static_cast<std::size_t>(2 * y * s + 2 * x);
        next[static_cast<std::size_t>(y * h + x)] = 0.25f * (level[i] + level[i + 1] + level[i + static_cast<std::size_t>(s)] + level[i + static_cast<std::size_t>(s) + 1]);
      }
    level = std::move(next);
  }
}

float Texture::texel(int x, int y) const { return levels_[0][blockIndex(size_, x, y)] * (1.0f / 255.0f); }

}  // namespace edgevio::sim
