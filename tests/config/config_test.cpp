#include "edgevio/config/config.h"

#include <gtest/gtest.h>

#include <set>
#include <sstream>
#include <type_traits>

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

TEST(Config, TheReferenceInDocsIsTheGeneratedOne) {
  std::ostringstream generated;
  writeConfigReference(generated);
  EXPECT_EQ(test::readFile(test::sourceDir() + "/docs/configuration.md"), generated.str())
      << "docs/configuration.md is out of date: edgevio --print-config-reference > docs/configuration.md";
}

TEST(Config, EveryOptionHasAKeyAUnitAndAMeaningOnce) {
  const Config c;
  std::size_t options = 0;
  forEachSection(c, [&](const char* section, const char*, const auto& s) {
    std::set<std::string> keys;
    for (const auto& f : std::decay_t<decltype(s)>::table().fields) {
      ++options;
      EXPECT_TRUE(keys.insert(f.key).second) << section << "." << f.key << " twice";
      EXPECT_GT(std::string(f.unit).size(), 0u) << section << "." << f.key;
      EXPECT_GT(f.meaning.size(), 10u) << section << "." << f.key;
      EXPECT_EQ(f.check(s), "") << section << "." << f.key << ": its default is invalid";
    }
  });
  EXPECT_GT(options, 100u);
}

TEST(Config, WriteThenReadRoundTrips) {
  Config c;
  c.dataset.stereo_sync_tolerance_s = 0.0012345678901;
  c.eval.alignment = eval::AlignmentKind::kSim3;
  c.eval.are_segments_m = {1.5, 3.0};
  std::ostringstream o;
  writeConfig(o, c);
  TempDir dir;
  const Config r = loadConfig(dir.write("c.yaml", o.str()));
  EXPECT_EQ(r.dataset.stereo_sync_tolerance_s, c.dataset.stereo_sync_tolerance_s);
  EXPECT_EQ(r.eval.alignment, eval::AlignmentKind::kSim3);
  EXPECT_EQ(r.eval.are_segments_m, c.eval.are_segments_m);
}

TEST(Config, PartialFileKeepsDefaults) {
  TempDir dir;
  std::vector<std::string> missing;
  const Config c = loadConfig(dir.write("c.yaml", "eval:\n  alignment: posyaw\n"), &missing);
  EXPECT_EQ(c.eval.alignment, eval::AlignmentKind::kPosYaw);
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
  EXPECT_NE(errorOf("eval:\n  alignment: affine\n").find(":2: 'eval.alignment': expected one of se3 | sim3 | posyaw | none"),
            std::string::npos);
  EXPECT_NE(errorOf("alignment:\n  max_iterations_per_level: 0\n").find("alignment.max_iterations_per_level: must be in [1, 100] (got 0)"),
            std::string::npos);
  EXPECT_NE(errorOf("estimator:\n  window_size: 30\n  visual_shared_fraction: 1\n").find(":3: invalid value: estimator.visual_shared_fraction"),
            std::string::npos);
  EXPECT_NE(errorOf("estimator:\n  coupling: tight\n  estimate_time_offset: true\n")
                .find("invalid value: estimator.coupling: tight does not estimate the camera-IMU calibration"),
            std::string::npos);
  EXPECT_EQ(errorOf("estimator:\n  coupling: tight\n"), "");
  EXPECT_NE(errorOf("dataset: 5\n").find("must be a mapping"), std::string::npos);
  EXPECT_NE(errorOf("dataset:\n  imu_gap_warning_s: [1\n").find("invalid YAML"), std::string::npos);
  EXPECT_NE(errorOf("eval:\n  association_tolerance_s: .nan\n").find("expected a number"), std::string::npos);
  EXPECT_NE(errorOf("\x01\x02\x03").find("c.yaml"), std::string::npos);
}

}  // namespace
}  // namespace edgevio
