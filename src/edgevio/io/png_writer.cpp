#include "edgevio/io/png_writer.h"

#include <zlib.h>

#include <cstdio>
#include <memory>
#include <vector>

#include "edgevio/common/error.h"

namespace edgevio::io {

namespace {

void put32(std::vector<unsigned char>& out, std::uint32_t v) {
  for (int s = 24; s >= 0; s -= 8) out.push_back(static_cast<unsigned char>(v >> s));
}

/// Appends a chunk: length, type, data, CRC-32 of type + data (PNG spec §5.3).
void chunk(std::vector<unsigned char>& out, const char* type, const unsigned char* data, std::size_t size) {
  put32(out, static_cast<std::uint32_t>(size));
  const std::size_t type_at = out.size();
  out.insert(out.end(), type, type + 4);
  out.insert(out.end(), data, data + size);
  const uLong crc = crc32(0L, out.data() + type_at, static_cast<uInt>(size + 4));
  put32(out, static_cast<std::uint32_t>(crc));
}

}  // namespace

void writePngGray8(const std::string& path, const cv::Mat& image, int zlib_level) {
  if (image.type() != CV_8UC1 || image.empty()) throw InputError(path, 0, "writePngGray8 needs a non-empty 8-bit grey image");
  const int w = image.cols, h = image.rows;
  // Filtered scanlines: a filter-type byte (2 = Up: x − the pixel above) per row.
  std::vector<unsigned char> raw(static_cast<std::size_t>(h) * (static_cast<std::size_t>(w) + 1));
  for (int y = 0; y < h; ++y) {
    unsigned char* row = &raw[static_cast<std::size_t>(y) * (static_cast<std::size_t>(w) + 1)];
    const unsigned char* cur = image.ptr<unsigned char>(y);
    const unsigned char* up = y > 0 ? image.ptr<unsigned char>(y - 1) : nullptr;
    row[0] = 2;
    for (int x = 0; x < w; ++x) row[x + 1] = static_cast<unsigned char>(cur[x] - (up ? up[x] : 0));
  }
  // Z_RLE: on sensor images (noise everywhere) long-distance matches are rare,
  // and run-length matching after the Up filter keeps most of the gain of full
  // deflate at several times its speed.
  z_stream zs{};
  if (deflateInit2(&zs, zlib_level, Z_DEFLATED, 15, 8, Z_RLE) != Z_OK) throw InputError(path, 0, "PNG compression failed");
  std::vector<unsigned char> z(deflateBound(&zs, static_cast<uLong>(raw.size())));
  zs.next_in = raw.data();
  zs.avail_in = static_cast<uInt>(raw.size());
  zs.next_out = z.data();
  zs.avail_out = static_cast<uInt>(z.size());
  const int rc = deflate(&zs, Z_FINISH);
  const std::size_t zsize = zs.total_out;
  deflateEnd(&zs);
  if (rc != Z_STREAM_END) throw InputError(path, 0, "PNG compression failed");

  std::vector<unsigned char> out = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  std::vector<unsigned char> ihdr;
  put32(ihdr, static_cast<std::uint32_t>(w));
  put32(ihdr, static_cast<std::uint32_t>(h));
  ihdr.insert(ihdr.end(), {8, 0, 0, 0, 0});  // bit depth 8, greyscale, deflate, adaptive filtering, no interlace
  chunk(out, "IHDR", ihdr.data(), ihdr.size());
  chunk(out, "IDAT", z.data(), zsize);
  chunk(out, "IEND", nullptr, 0);

  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "wb"), &std::fclose);
  if (!f || std::fwrite(out.data(), 1, out.size(), f.get()) != out.size())
    throw InputError(path, 0, "cannot write image (is the disk full or the folder missing?)");
}

}  // namespace edgevio::io
