#include <gtest/gtest.h>

#include <sstream>

#include "common/mini_dataset.h"
#include "edgevio/cli/commands.h"

namespace edgevio::cli {
namespace {

InfoArgs infoOf(const std::string& dataset) {
  InfoArgs a;
  a.source.path = dataset;
  return a;
}

TEST(InfoCommand, RealMicroFolderFigures) {
  EDGEVIO_REQUIRE_SHARED_DATA("euroc/V1_01_easy_micro");
  std::ostringstream out, err;
  ASSERT_EQ(info(infoOf(data_path), out, err), kExitOk) << err.str();
  const std::string j = out.str();
  EXPECT_NE(j.find("\"stereo_pairs\": 95,"), std::string::npos) << j;
  EXPECT_NE(j.find("\"imu_samples\": 29120,"), std::string::npos) << j;
  EXPECT_NE(j.find("\"imu_rate_hz\": 200,"), std::string::npos) << j;
  EXPECT_NE(j.find("\"cam1_frames\": 95,"), std::string::npos) << j;
  EXPECT_NE(j.find("1403715278012143104.png"), std::string::npos) << j;  // one of the missing cam1 files
}

TEST(InfoCommand, ABagsFiguresAreItsFoldersAndItNamesItsTopics) {
  test::TempDir dir, out_dir;
  const std::string root = test::writeMiniDataset(dir);
  std::ostringstream folder, err, bag;
  ASSERT_EQ(info(infoOf(root), folder, err), kExitOk) << err.str();
  ConvertArgs c;
  c.source.path = root;
  c.out = out_dir.file("mini.bag");
  c.compression = "lz4";
  std::ostringstream ignored;
  ASSERT_EQ(convert(c, ignored, err), kExitOk) << err.str();
  ASSERT_EQ(info(infoOf(c.out), bag, err), kExitOk) << err.str();
  // The same figures after the "dataset" line; the bag's topics besides.
  const auto after = [](const std::string& j, const std::string& from, const std::string& to) {
    const std::size_t a = j.find(from);
    return j.substr(a, j.find(to) - a);
  };
  EXPECT_EQ(after(bag.str(), "\"cam0_frames\"", "\"topics\""), after(folder.str(), "\"cam0_frames\"", "\"warnings\"")) << bag.str();
  EXPECT_NE(bag.str().find("\"cam0\": \"/cam0/image_raw\""), std::string::npos) << bag.str();
  EXPECT_NE(bag.str().find("\"imu\": \"/imu0\""), std::string::npos) << bag.str();
  EXPECT_EQ(folder.str().find("\"topics\""), std::string::npos);
}

TEST(InfoCommand, BadInputIsExitOneWithMessage) {
  test::TempDir dir;
  std::ostringstream out, err;
  EXPECT_EQ(info(infoOf(dir.path() + "/missing"), out, err), kExitError);
  EXPECT_NE(err.str().find("not found"), std::string::npos);
  const std::string root = test::writeMiniDataset(dir);
  dir.write("mav0/imu0/data.csv", "#\n1,2,3\n");
  std::ostringstream out2, err2;
  EXPECT_EQ(info(infoOf(root), out2, err2), kExitError);
  EXPECT_NE(err2.str().find("imu0/data.csv:2"), std::string::npos) << err2.str();
}

}  // namespace
}  // namespace edgevio::cli
