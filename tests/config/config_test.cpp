#include "edgevio/config/config.h"

#include <gtest/gtest.h>

#include <sstream>

#include "common/test_support.h"
#include "edgevio/common/error.h"

namespace edgevio {
namespace {

using test::TempDir;

std::string errorOf(const std::string& yaml) {
  TempDir dir;
  try {
    loadConfig(dir.write("c.yaml", yaml));
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(Config, DefaultsAreValid) { EXPECT_EQ(Config{}.validate(), ""); }

TEST(Config, ShippedFileDocumentsEveryKeyWithDefaultValues) {
  std::vector<std::string> missing;
  const Config c = loadConfig(test::sourceDir() + "/config/euroc.yaml", &missing);
  EXPECT_TRUE(missing.empty()) << "config/euroc.yaml lacks " << missing.front()
                               << " (regenerate it: edgevio --print-config > config/euroc.yaml)";
  std::ostringstream shipped, defaults;
  writeConfig(shipped, c);
  writeConfig(defaults, Config{});
  EXPECT_EQ(shipped.str(), defaults.str()) << "config/euroc.yaml values differ from the code's defaults";
}

TEST(Config, WriteThenReadRoundTrips) {
  Config c;
  c.dataset.stereo_sync_tolerance_s = 0.0012345678901;
  c.eval.alignment = "sim3";
  c.eval.are_segments_m = {1.5, 3.0};
  std::ostringstream o;
  writeConfig(o, c);
  TempDir dir;
  const Config r = loadConfig(dir.write("c.yaml", o.str()));
  EXPECT_EQ(r.dataset.stereo_sync_tolerance_s, c.dataset.stereo_sync_tolerance_s);
  EXPECT_EQ(r.eval.alignment, "sim3");
  EXPECT_EQ(r.eval.are_segments_m, c.eval.are_segments_m);
}

TEST(Config, PartialFileKeepsDefaults) {
  TempDir dir;
  std::vector<std::string> missing;
  const Config c = loadConfig(dir.write("c.yaml", "eval:\n  alignment: posyaw\n"), &missing);
  EXPECT_EQ(c.eval.alignment, "posyaw");
  EXPECT_EQ(c.dataset.stereo_sync_tolerance_s, Config{}.dataset.stereo_sync_tolerance_s);
  EXPECT_FALSE(missing.empty());
}

TEST(Config, ErrorsNameFileLineAndKey) {
  EXPECT_NE(errorOf("dataset:\n  stereo_sync_tolerance: 0.1\n").find(":2: unknown key 'dataset.stereo_sync_tolerance'"),
            std::string::npos);
  EXPECT_NE(errorOf("datset:\n  x: 1\n").find(":1: unknown section 'datset'"), std::string::npos);
  EXPECT_NE(errorOf("eval:\n  association_tolerance_s: fast\n").find(":2: 'eval.association_tolerance_s': expected a number"),
            std::string::npos);
  EXPECT_NE(errorOf("eval:\n  rpe_deltas_m: 3\n").find("expected a list of numbers"), std::string::npos);
  EXPECT_NE(errorOf("eval:\n  alignment: affine\n").find("eval.alignment: must be one of"), std::string::npos);
  EXPECT_NE(errorOf("dataset: 5\n").find("must be a mapping"), std::string::npos);
  EXPECT_NE(errorOf("dataset:\n  imu_gap_warning_s: [1\n").find("invalid YAML"), std::string::npos);
  EXPECT_NE(errorOf("eval:\n  association_tolerance_s: .nan\n").find("expected a number"), std::string::npos);
  EXPECT_NE(errorOf("\x01\x02\x03").find("c.yaml"), std::string::npos);
}

}  // namespace
}  // namespace edgevio
