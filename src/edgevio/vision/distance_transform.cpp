#include "edgevio/vision/distance_transform.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

namespace edgevio::vision {

DistanceTransform::DistanceTransform(const cv::Mat& edges, const cv::Mat& image) {
  cv::Mat background;
  cv::compare(edges, 0, background, cv::CMP_EQ);  // distanceTransform measures to the nearest zero pixel
  cv::distanceTransform(background, dist_, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
  if (!image.empty()) buildLines(edges, image, background);
  gu_.create(dist_.size(), CV_32FC1);
  gv_.create(dist_.size(), CV_32FC1);
  const int W = dist_.cols, H = dist_.rows;
  for (int v = 0; v < H; ++v) {
    const float* d = dist_.ptr<float>(v);
    const float* up = dist_.ptr<float>(std::max(v - 1, 0));
    const float* down = dist_.ptr<float>(std::min(v + 1, H - 1));
    float* gu = gu_.ptr<float>(v);
    float* gv = gv_.ptr<float>(v);
    const float sv = (v == 0 || v == H - 1) ? 1.0f : 0.5f;
    for (int u = 0; u < W; ++u) {
      const int ul = std::max(u - 1, 0), ur = std::min(u + 1, W - 1);
      gu[u] = (d[ur] - d[ul]) * ((u == 0 || u == W - 1) ? 1.0f : 0.5f);
      gv[u] = (down[u] - up[u]) * sv;
    }
  }
}

void DistanceTransform::buildLines(const cv::Mat& edges, const cv::Mat& image, const cv::Mat& background) {
  // Nearest edge pixel of every pixel: OpenCV labels each zero pixel of
  // `background` (an edge pixel) and propagates the label of the nearest one.
  cv::Mat unused, labels;
  cv::distanceTransform(background, unused, labels, cv::DIST_L2, cv::DIST_MASK_5, cv::DIST_LABEL_PIXEL);
  cv::Mat gx, gy;
  cv::Sobel(image, gx, CV_32F, 1, 0, 3);
  cv::Sobel(image, gy, CV_32F, 0, 1, 3);
  const auto magnitude = [&](double x, double y) {
    const int x0 = std::clamp(static_cast<int>(x), 0, image.cols - 2), y0 = std::clamp(static_cast<int>(y), 0, image.rows - 2);
    const float a = static_cast<float>(x - x0), b = static_cast<float>(y - y0);
    const auto m = [&](int xx, int yy) { return std::hypot(gx.at<float>(yy, xx), gy.at<float>(yy, xx)); };
    return (1 - b) * ((1 - a) * m(x0, y0) + a * m(x0 + 1, y0)) + b * ((1 - a) * m(x0, y0 + 1) + a * m(x0 + 1, y0 + 1));
  };
  // Label → line index. Labels of edge pixels are unique, assigned in scan order.
  int max_label = 0;
  for (int v = 0; v < labels.rows; ++v)
    for (int u = 0; u < labels.cols; ++u) max_label = std::max(max_label, labels.at<int>(v, u));
  std::vector<int> line_of_label(static_cast<std::size_t>(max_label) + 1, -1);
  for (int v = 0; v < edges.rows; ++v)
    for (int u = 0; u < edges.cols; ++u) {
      if (!edges.at<std::uint8_t>(v, u)) continue;
      float nx = gx.at<float>(v, u), ny = gy.at<float>(v, u);
      const float norm = std::hypot(nx, ny);
      Eigen::Vector4f line(static_cast<float>(u), static_cast<float>(v), 1.0f, 0.0f);
      if (norm > 1e-6f) {
        nx /= norm;
        ny /= norm;
        // Parabola through the gradient magnitude at −1, 0, +1 px along n.
        const float m0 = norm, mm = magnitude(u - nx, v - ny), mp = magnitude(u + nx, v + ny);
        const float den = mm - 2 * m0 + mp;
        const float offset = den < -1e-6f ? std::clamp(0.5f * (mm - mp) / den, -0.5f, 0.5f) : 0.0f;
        line = Eigen::Vector4f(static_cast<float>(u) + offset * nx, static_cast<float>(v) + offset * ny, nx, ny);
      }
      line_of_label[static_cast<std::size_t>(labels.at<int>(v, u))] = static_cast<int>(lines_.size());
      lines_.push_back(line);
    }
  nearest_.create(labels.size(), CV_32SC1);
  for (int v = 0; v < labels.rows; ++v)
    for (int u = 0; u < labels.cols; ++u) nearest_.at<int>(v, u) = line_of_label[static_cast<std::size_t>(labels.at<int>(v, u))];
}

void DistanceTransform::nearestLine(double u, double v, Vec2* point, Vec2* normal) const {
  const int x = std::clamp(static_cast<int>(u + 0.5), 0, nearest_.cols - 1);
  const int y = std::clamp(static_cast<int>(v + 0.5), 0, nearest_.rows - 1);
  const int i = nearest_.at<int>(y, x);
  if (i < 0) {  // no edge at all in the image
    *point = Vec2(u, v);
    *normal = Vec2(1.0, 0.0);
    return;
  }
  const Eigen::Vector4f& l = lines_[static_cast<std::size_t>(i)];
  *point = Vec2(l[0], l[1]);
  *normal = Vec2(l[2], l[3]);
}

namespace {
inline float bilinear(const cv::Mat& m, int u0, int v0, float a, float b) {
  const float* r0 = m.ptr<float>(v0);
  const float* r1 = m.ptr<float>(v0 + 1);
  return (1 - b) * ((1 - a) * r0[u0] + a * r0[u0 + 1]) + b * ((1 - a) * r1[u0] + a * r1[u0 + 1]);
}
}  // namespace

float DistanceTransform::value(double u, double v) const {
  const int u0 = static_cast<int>(u), v0 = static_cast<int>(v);
  return bilinear(dist_, u0, v0, static_cast<float>(u - u0), static_cast<float>(v - v0));
}

void DistanceTransform::valueAndGradient(double u, double v, float* value, float* du, float* dv) const {
  const int u0 = static_cast<int>(u), v0 = static_cast<int>(v);
  const float a = static_cast<float>(u - u0), b = static_cast<float>(v - v0);
  *value = bilinear(dist_, u0, v0, a, b);
  *du = bilinear(gu_, u0, v0, a, b);
  *dv = bilinear(gv_, u0, v0, a, b);
}

}  // namespace edgevio::vision
