// The fast PNG reader: every row filter of RFC 2083 decoded exactly (on a
// file written here row filter by row filter), agreement with OpenCV on its
// own and on the simulator's files, and a clean refusal of anything else.
#include "edgevio/io/png_reader.h"

#include <gtest/gtest.h>
#include <zlib.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <cstdlib>
#include <fstream>
#include <vector>

#include "common/test_support.h"
#include "edgevio/io/euroc_dataset.h"
#include "edgevio/io/png_writer.h"
#include "edgevio/sim/random.h"

namespace edgevio::io {
namespace {

using test::TempDir;

cv::Mat texture(int w, int h, std::uint64_t seed) {
  sim::Rng rng(seed);
  cv::Mat m(h, w, CV_8UC1);
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u)
      m.at<std::uint8_t>(v, u) = static_cast<std::uint8_t>((u * 3 + v * 5) % 256 / 2 + static_cast<int>(rng.uniform() * 120));
  return m;
}

void put32(std::vector<std::uint8_t>* out, std::uint32_t x) {
  for (int s = 24; s >= 0; s -= 8) out->push_back(static_cast<std::uint8_t>(x >> s));
}

void chunk(std::vector<std::uint8_t>* out, const char* type, const std::vector<std::uint8_t>& data) {
  put32(out, static_cast<std::uint32_t>(data.size()));
  const std::size_t start = out->size();
  out->insert(out->end(), type, type + 4);
  out->insert(out->end(), data.begin(), data.end());
  put32(out, static_cast<std::uint32_t>(crc32(0, out->data() + start, static_cast<uInt>(data.size() + 4))));
}

/// An 8-bit grey PNG whose row v uses filter v mod 5, the filters applied as RFC 2083 §6 defines them.
std::vector<std::uint8_t> pngWithEveryFilter(const cv::Mat& img) {
  std::vector<std::uint8_t> raw;
  for (int v = 0; v < img.rows; ++v) {
    const int f = v % 5;
    raw.push_back(static_cast<std::uint8_t>(f));
    for (int u = 0; u < img.cols; ++u) {
      const int x = img.at<std::uint8_t>(v, u), a = u > 0 ? img.at<std::uint8_t>(v, u - 1) : 0,
                b = v > 0 ? img.at<std::uint8_t>(v - 1, u) : 0, c = u > 0 && v > 0 ? img.at<std::uint8_t>(v - 1, u - 1) : 0;
      const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
      const int predictor[5] = {0, a, b, (a + b) / 2, pa <= pb && pa <= pc ? a : pb <= pc ? b : c};
      raw.push_back(static_cast<std::uint8_t>(x - predictor[f]));
    }
  }
  std::vector<std::uint8_t> z(compressBound(static_cast<uLong>(raw.size())));
  uLongf zsize = static_cast<uLongf>(z.size());
  EXPECT_EQ(compress2(z.data(), &zsize, raw.data(), static_cast<uLong>(raw.size()), 6), Z_OK);
  z.resize(zsize);
  std::vector<std::uint8_t> png = {137, 80, 78, 71, 13, 10, 26, 10}, ihdr;
  put32(&ihdr, static_cast<std::uint32_t>(img.cols));
  put32(&ihdr, static_cast<std::uint32_t>(img.rows));
  ihdr.insert(ihdr.end(), {8, 0, 0, 0, 0});
  chunk(&png, "IHDR", ihdr);
  // Two IDAT chunks: the stream may be split anywhere.
  chunk(&png, "IDAT", std::vector<std::uint8_t>(z.begin(), z.begin() + static_cast<long>(z.size() / 2)));
  chunk(&png, "IDAT", std::vector<std::uint8_t>(z.begin() + static_cast<long>(z.size() / 2), z.end()));
  chunk(&png, "IEND", {});
  return png;
}

void writeBytes(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), static_cast<long>(bytes.size()));
}

bool same(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() && cv::countNonZero(a != b) == 0;
}

TEST(PngReader, DecodesEveryRowFilterExactly) {
  TempDir dir;
  const cv::Mat img = texture(37, 23, 5);
  writeBytes(dir.file("f.png"), pngWithEveryFilter(img));
  const cv::Mat fast = readPngGray8(dir.file("f.png"));
  ASSERT_FALSE(fast.empty());
  EXPECT_TRUE(same(fast, img));
  EXPECT_TRUE(same(fast, cv::imread(dir.file("f.png"), cv::IMREAD_GRAYSCALE)));
}

TEST(PngReader, AgreesWithOpenCvOnItsFilesAndTheSimulators) {
  TempDir dir;
  const cv::Mat img = texture(752, 480, 9);
  cv::imwrite(dir.file("cv.png"), img);  // libpng chooses a filter per row
  writePngGray8(dir.file("sim.png"), img);
  for (const char* name : {"cv.png", "sim.png"}) {
    const cv::Mat fast = readPngGray8(dir.file(name));
    ASSERT_FALSE(fast.empty()) << name;
    EXPECT_TRUE(same(fast, img)) << name;
  }
}

TEST(PngReader, LeavesEverythingElseToOpenCv) {
  TempDir dir;
  const cv::Mat img = texture(40, 30, 3);
  cv::Mat colour, deep;
  cv::cvtColor(img, colour, cv::COLOR_GRAY2BGR);
  img.convertTo(deep, CV_16U, 256);
  cv::imwrite(dir.file("colour.png"), colour);
  cv::imwrite(dir.file("deep.png"), deep);
  EXPECT_TRUE(readPngGray8(dir.file("colour.png")).empty());
  EXPECT_TRUE(readPngGray8(dir.file("deep.png")).empty());
  // ... and decodeGrayImage still reads them (through OpenCV), as before.
  EXPECT_TRUE(same(decodeGrayImage(dir.file("colour.png")), cv::imread(dir.file("colour.png"), cv::IMREAD_GRAYSCALE)));
  EXPECT_FALSE(decodeGrayImage(dir.file("deep.png")).empty());

  // Damaged files: a flipped data byte (CRC mismatch), a truncation, no file, not a PNG.
  std::vector<std::uint8_t> png = pngWithEveryFilter(img);
  std::vector<std::uint8_t> flipped = png;
  flipped[60] ^= 0x40;
  writeBytes(dir.file("flipped.png"), flipped);
  writeBytes(dir.file("short.png"), std::vector<std::uint8_t>(png.begin(), png.begin() + static_cast<long>(png.size() / 2)));
  writeBytes(dir.file("text.png"), {'h', 'e', 'l', 'l', 'o'});
  for (const char* name : {"flipped.png", "short.png", "missing.png", "text.png"})
    EXPECT_TRUE(readPngGray8(dir.file(name)).empty()) << name;
}

TEST(PngReader, RealEurocImageMatchesOpenCv) {
  EDGEVIO_REQUIRE_SHARED_DATA("euroc/V1_01_easy_micro");
  EurocDataset d(data_path, DatasetOptions{});
  const std::string& path = d.stereoPairs().front().left.path;
  const cv::Mat fast = readPngGray8(path);
  ASSERT_FALSE(fast.empty()) << path;
  EXPECT_TRUE(same(fast, cv::imread(path, cv::IMREAD_GRAYSCALE)));
}

}  // namespace
}  // namespace edgevio::io
