#include "edgevio/io/png_reader.h"

#include <libdeflate.h>

#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <algorithm>
#include <memory>
#include <vector>

namespace edgevio::io {

namespace {

std::uint32_t bigEndian32(const std::uint8_t* p) {
  return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) | std::uint32_t{p[3]};
}

/// Paeth predictor (RFC 2083 §6.6), written so that it compiles to selects.
inline int paeth(int a, int b, int c) {
  const int pa = std::abs(b - c), pb = std::abs(a - c), pc = std::abs(a + b - 2 * c);
  const int ab = pb < pa ? b : a;
  return pc < std::min(pa, pb) ? c : ab;
}

struct Decompressor {
  void operator()(libdeflate_decompressor* d) const { libdeflate_free_decompressor(d); }
};

}  // namespace

cv::Mat readPngGray8(const std::string& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) return {};
  const std::streamoff size = in.tellg();
  if (size <= 0) return {};
  std::vector<std::uint8_t> file(static_cast<std::size_t>(size));
  in.seekg(0);
  if (!in.read(reinterpret_cast<char*>(file.data()), size)) return {};
  return decodePngGray8(file);
}

cv::Mat decodePngGray8(const std::vector<std::uint8_t>& file) {
  static constexpr std::uint8_t kSignature[8] = {137, 80, 78, 71, 13, 10, 26, 10};
  if (file.size() < 8 || !std::equal(kSignature, kSignature + 8, file.begin())) return {};

  // Chunks: length, type, data, CRC-32 of type and data. Every CRC is
  // checked, and the order libpng insists on (RFC 2083 §3.2, §4.3): IHDR
  // first and once, the IDAT chunks consecutive; any other critical chunk
  // (a name starting in upper case) is for the general decoder to judge.
  int width = 0, height = 0;
  std::vector<std::uint8_t> compressed;
  bool header = false, end = false, idat_ended = false;
  for (std::size_t at = 8; at + 12 <= file.size() && !end;) {
    const std::uint32_t length = bigEndian32(&file[at]);
    if (length > file.size() - at - 12) return {};
    const std::uint8_t* type = &file[at + 4];
    const std::uint8_t* data = type + 4;
    if (libdeflate_crc32(0, type, length + 4) != bigEndian32(data + length)) return {};
    const std::string name(reinterpret_cast<const char*>(type), 4);
    if ((at == 8) != (name == "IHDR")) return {};
    if (!compressed.empty() && name != "IDAT") idat_ended = true;
    if (name == "IHDR") {
      // Only 8-bit greyscale (colour type 0), standard compression and filters, no interlacing.
      if (length != 13 || data[8] != 8 || data[9] != 0 || data[10] != 0 || data[11] != 0 || data[12] != 0) return {};
      width = static_cast<int>(bigEndian32(data));
      height = static_cast<int>(bigEndian32(data + 4));
      if (width <= 0 || height <= 0 || width > 1 << 15 || height > 1 << 15) return {};
      header = true;
    } else if (name == "IDAT") {
      if (idat_ended) return {};
      compressed.insert(compressed.end(), data, data + length);
    } else if (name == "IEND") {
      end = true;
    } else if (name[0] >= 'A' && name[0] <= 'Z') {
      return {};
    }
    at += 12 + length;
  }
  if (!header || !end || compressed.empty()) return {};

  // Each row: one filter-type byte, then the width's bytes.
  const std::size_t stride = static_cast<std::size_t>(width) + 1;
  std::vector<std::uint8_t> raw(stride * static_cast<std::size_t>(height));
  const std::unique_ptr<libdeflate_decompressor, Decompressor> d(libdeflate_alloc_decompressor());
  if (!d || libdeflate_zlib_decompress(d.get(), compressed.data(), compressed.size(), raw.data(), raw.size(), nullptr) !=
                LIBDEFLATE_SUCCESS)
    return {};

  cv::Mat image(height, width, CV_8UC1);
  const std::vector<std::uint8_t> zeros(static_cast<std::size_t>(width), 0);
  for (int v = 0; v < height; ++v) {
    const std::uint8_t* row = &raw[stride * static_cast<std::size_t>(v)];
    const std::uint8_t* x = row + 1;
    std::uint8_t* o = image.ptr<std::uint8_t>(v);
    // Filters (RFC 2083 §6.2-6.6) with one byte per pixel: "left" is the
    // previous pixel of the row, "up" the pixel above; both 0 outside the image.
    const std::uint8_t* up = v > 0 ? image.ptr<std::uint8_t>(v - 1) : zeros.data();
    switch (row[0]) {
      case 0:
        std::copy(x, x + width, o);
        break;
      case 1:
        o[0] = x[0];
        for (int u = 1; u < width; ++u) o[u] = static_cast<std::uint8_t>(x[u] + o[u - 1]);
        break;
      case 2:
        for (int u = 0; u < width; ++u) o[u] = static_cast<std::uint8_t>(x[u] + up[u]);
        break;
      case 3:
        o[0] = static_cast<std::uint8_t>(x[0] + (up[0] >> 1));
        for (int u = 1; u < width; ++u) o[u] = static_cast<std::uint8_t>(x[u] + ((o[u - 1] + up[u]) >> 1));
        break;
      case 4:
        o[0] = static_cast<std::uint8_t>(x[0] + up[0]);  // Paeth(0, b, 0) = b
        for (int u = 1; u < width; ++u) o[u] = static_cast<std::uint8_t>(x[u] + paeth(o[u - 1], up[u], up[u - 1]));
        break;
      default:
        return {};
    }
  }
  return image;
}

}  // namespace edgevio::io
