#pragma once
// A fast reader of the PNG files a stereo dataset is made of: 8-bit
// greyscale, not interlaced (EuRoC, TUM-VI, edgevio's simulator). libpng
// inflates with zlib; libdeflate does it two to three times faster, and the
// five row filters (RFC 2083 §6) are undone here. Anything else (colour,
// 16 bits, interlacing, a damaged file) is left to OpenCV: the result is then
// exactly what cv::imread gives.
#include <opencv2/core.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace edgevio::io {

/// The image as CV_8UC1, or empty when the file is not a well-formed 8-bit
/// greyscale non-interlaced PNG (the caller falls back to a general decoder).
cv::Mat readPngGray8(const std::string& path);
/// The same for a PNG file's bytes in memory (a ROS CompressedImage's data).
cv::Mat decodePngGray8(const std::vector<std::uint8_t>& file);

}  // namespace edgevio::io
