#pragma once
// The alignment picture: the one image that tells whether a frame's
// alignment worked. The current frame's image at level 0 of its pyramid,
// where the alignment's residuals live (half the camera's resolution;
// darkened), its Canny edges (white), and the keyframe's reference edge points at
// the alignment's pose, coloured by how the finest level weighed them:
// inliers green, outliers red, points whose nearest edge failed the normal
// check blue (tracking/edge_alignment.h, reprojectReferencePoints). Reference
// points landing on the white edges mean the alignment found the pose.
#include <opencv2/core.hpp>

#include <cstdint>
#include <vector>

#include "edgevio/tracking/edge_alignment.h"

namespace edgevio::tracking {

/// What a picture is drawn from; cheap to keep (the images are shared, not copied).
struct AlignmentPicture {
  cv::Mat image;   ///< the image the picture is drawn on (CV_8UC1): level 0, or any multiple of its size
  cv::Mat edges;   ///< level-0 Canny edges (CV_8UC1, 255 on edges)
  std::vector<ReprojectedPoint> points;  ///< level-0 pixels; empty when the frame was not aligned
};

/// BGR colours of the point classes (also the legend of the viewer).
cv::Scalar pointColour(PointFit fit);

/// The picture at the image's resolution (CV_8UC3); empty when the image is.
cv::Mat drawAlignmentPicture(const AlignmentPicture& picture);

/// The picture as a JPEG file's bytes (quality 0-100).
std::vector<std::uint8_t> encodeJpeg(const cv::Mat& bgr, int quality);

}  // namespace edgevio::tracking
