#pragma once
// A fast writer of 8-bit greyscale PNG files for the simulator. OpenCV's
// encoder lets libpng try every row filter, which costs ~10 ms per 752x480
// image; one fixed filter ("Up", RFC 2083 §6.3) with zlib's run-length
// strategy is several times faster at a similar size on sensor images (see
// bench/simulator_bench). Decoding stays with OpenCV.
#include <opencv2/core.hpp>

#include <string>

namespace edgevio::io {

/// Writes a CV_8UC1 image; throws InputError when the file cannot be written.
void writePngGray8(const std::string& path, const cv::Mat& image, int zlib_level = 1);

}  // namespace edgevio::io
