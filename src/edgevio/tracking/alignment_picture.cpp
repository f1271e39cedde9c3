#include "edgevio/tracking/alignment_picture.h"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>

namespace edgevio::tracking {

cv::Scalar pointColour(PointFit fit) {
  switch (fit) {
    case PointFit::kInlier: return {80, 220, 60};
    case PointFit::kOutlier: return {40, 40, 240};
    case PointFit::kOtherEdge: return {255, 140, 30};
  }
  return {};
}

cv::Mat drawAlignmentPicture(const AlignmentPicture& p) {
  if (p.image.empty()) return {};
  cv::Mat grey;
  p.image.convertTo(grey, CV_8U, 0.45);  // darkened: the edges and points stand out
  cv::Mat out;
  cv::cvtColor(grey, out, cv::COLOR_GRAY2BGR);
  // An image s times level 0's size: level-0 pixel (u, v) covers pixels
  // s·u .. s·u + s − 1, centred at s·u + (s − 1)/2.
  const double sx = p.edges.empty() ? 1.0 : static_cast<double>(p.image.cols) / p.edges.cols;
  const double sy = p.edges.empty() ? 1.0 : static_cast<double>(p.image.rows) / p.edges.rows;
  if (!p.edges.empty()) {
    cv::Mat edges = p.edges;
    if (edges.size() != p.image.size()) cv::resize(p.edges, edges, p.image.size(), 0, 0, cv::INTER_NEAREST);
    out.setTo(cv::Scalar(190, 190, 190), edges);
  }
  const int radius = sx >= 2.0 ? 1 : 0;  // a point stays about one level-0 pixel
  for (const ReprojectedPoint& q : p.points) {
    const int x = static_cast<int>(std::lround(sx * q.u + 0.5 * (sx - 1.0)));
    const int y = static_cast<int>(std::lround(sy * q.v + 0.5 * (sy - 1.0)));
    if (x < 0 || y < 0 || x >= out.cols || y >= out.rows) continue;
    if (radius == 0)
      out.at<cv::Vec3b>(y, x) = cv::Vec3b(static_cast<uchar>(pointColour(q.fit)[0]), static_cast<uchar>(pointColour(q.fit)[1]),
                                          static_cast<uchar>(pointColour(q.fit)[2]));
    else
      cv::circle(out, {x, y}, radius, pointColour(q.fit), cv::FILLED, cv::LINE_8);
  }
  return out;
}

std::vector<std::uint8_t> encodeJpeg(const cv::Mat& bgr, int quality) {
  std::vector<std::uint8_t> bytes;
  if (!bgr.empty()) cv::imencode(".jpg", bgr, bytes, {cv::IMWRITE_JPEG_QUALITY, quality});
  return bytes;
}

}  // namespace edgevio::tracking
