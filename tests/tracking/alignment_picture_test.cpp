// The alignment picture: where its edges and points are drawn, and in which colours.
#include "edgevio/tracking/alignment_picture.h"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

namespace edgevio::tracking {
namespace {

cv::Vec3b colourAt(const cv::Mat& bgr, int x, int y) { return bgr.at<cv::Vec3b>(y, x); }

cv::Vec3b asVec(const cv::Scalar& s) {
  return {static_cast<uchar>(s[0]), static_cast<uchar>(s[1]), static_cast<uchar>(s[2])};
}

TEST(AlignmentPicture, DrawsLevelZeroEdgesAndPointsAtFullResolution) {
  AlignmentPicture p;
  p.image = cv::Mat(480, 752, CV_8UC1, cv::Scalar(200));
  p.edges = cv::Mat::zeros(240, 376, CV_8UC1);
  p.edges.at<uchar>(100, 50) = 255;
  // Level-0 pixel (u, v) is centred on full-resolution pixel 2u + 0.5: points
  // at (10, 20), (200, 30) and (300, 200) cover full pixels around (20.5, 40.5), ...
  p.points = {{10.f, 20.f, PointFit::kInlier}, {200.f, 30.f, PointFit::kOutlier}, {300.f, 200.f, PointFit::kOtherEdge}};
  const cv::Mat out = drawAlignmentPicture(p);
  ASSERT_EQ(out.type(), CV_8UC3);
  ASSERT_EQ(out.size(), p.image.size());
  // The edge pixel covers the 2x2 block at (100, 200).
  for (int dy = 0; dy < 2; ++dy)
    for (int dx = 0; dx < 2; ++dx) EXPECT_EQ(colourAt(out, 100 + dx, 200 + dy), colourAt(out, 100, 200));
  EXPECT_NE(colourAt(out, 100, 200), colourAt(out, 0, 0));
  // The background is darkened, still grey.
  const cv::Vec3b bg = colourAt(out, 0, 0);
  EXPECT_LT(bg[0], 200);
  EXPECT_EQ(bg[0], bg[1]);
  EXPECT_EQ(bg[1], bg[2]);
  // Each point in its class's colour, rounded to the nearest pixel of 2u + 0.5.
  EXPECT_EQ(colourAt(out, 21, 41), asVec(pointColour(PointFit::kInlier)));
  EXPECT_EQ(colourAt(out, 401, 61), asVec(pointColour(PointFit::kOutlier)));
  EXPECT_EQ(colourAt(out, 601, 401), asVec(pointColour(PointFit::kOtherEdge)));
  // The three classes and the edges are told apart.
  EXPECT_NE(pointColour(PointFit::kInlier), pointColour(PointFit::kOutlier));
  EXPECT_NE(pointColour(PointFit::kInlier), pointColour(PointFit::kOtherEdge));
  EXPECT_NE(pointColour(PointFit::kOutlier), pointColour(PointFit::kOtherEdge));
}

TEST(AlignmentPicture, AtLevelZeroSizeEachPointIsOnePixel) {
  // What a run draws: the level-0 image itself, so points and edges land on
  // their own pixels.
  AlignmentPicture p;
  p.image = cv::Mat(240, 376, CV_8UC1, cv::Scalar(100));
  p.edges = cv::Mat::zeros(240, 376, CV_8UC1);
  p.edges.at<uchar>(7, 9) = 255;
  p.points = {{100.4f, 50.6f, PointFit::kOutlier}};
  const cv::Mat out = drawAlignmentPicture(p);
  ASSERT_EQ(out.size(), p.image.size());
  EXPECT_EQ(colourAt(out, 100, 51), asVec(pointColour(PointFit::kOutlier)));
  for (const auto& [x, y] : {std::pair{99, 51}, std::pair{101, 51}, std::pair{100, 50}, std::pair{100, 52}})
    EXPECT_EQ(colourAt(out, x, y), colourAt(out, 0, 0)) << x << "," << y;
  EXPECT_NE(colourAt(out, 9, 7), colourAt(out, 0, 0));   // the edge pixel
  EXPECT_EQ(colourAt(out, 10, 7), colourAt(out, 0, 0));  // and only it
}

TEST(AlignmentPicture, EncodesAJpegThatDecodesToThePicture) {
  AlignmentPicture p;
  p.image = cv::Mat(48, 64, CV_8UC1, cv::Scalar(120));
  const cv::Mat drawn = drawAlignmentPicture(p);
  const std::vector<std::uint8_t> jpeg = encodeJpeg(drawn, 90);
  ASSERT_GT(jpeg.size(), 4u);
  EXPECT_EQ(jpeg[0], 0xFF);  // the JPEG start-of-image marker
  EXPECT_EQ(jpeg[1], 0xD8);
  const cv::Mat decoded = cv::imdecode(jpeg, cv::IMREAD_COLOR);
  ASSERT_EQ(decoded.size(), drawn.size());
  EXPECT_LT(cv::norm(decoded, drawn, cv::NORM_INF), 4.0);  // a flat image survives JPEG within rounding
}

TEST(AlignmentPicture, NothingToDrawGivesNothing) {
  EXPECT_TRUE(drawAlignmentPicture({}).empty());
  EXPECT_TRUE(encodeJpeg(cv::Mat(), 80).empty());
}

}  // namespace
}  // namespace edgevio::tracking
