// `edgevio view` on bad run folders: errors that name the file, never a broken page.
#include "edgevio/view/run_view.h"

#include <gtest/gtest.h>

#include <fstream>

#include "common/test_support.h"
#include "edgevio/common/error.h"
#include "edgevio/pipeline/frame_record.h"

namespace edgevio::view {
namespace {

TEST(RunView, AFolderWithoutFramesCsvIsNotARunFolder) {
  const test::TempDir dir;
  std::vector<std::string> notes;
  test::expectInputError([&] { runViewJson(dir.path(), eval::EvalOptions{}, &notes); }, {dir.path(), "no frames.csv"});
}

TEST(RunView, ASummaryCutShortIsAnErrorNamingIt) {
  const test::TempDir dir;
  std::ofstream(dir.file("frames.csv")) << pipeline::frameHeader() << "\n";
  std::ofstream(dir.file("summary.json")) << "{\n  \"mode\": \"edge-only\",\n  \"frames\": [1, 2";
  std::vector<std::string> notes;
  test::expectInputError([&] { runViewJson(dir.path(), eval::EvalOptions{}, &notes); }, {"summary.json", "invalid YAML"});
}

}  // namespace
}  // namespace edgevio::view
