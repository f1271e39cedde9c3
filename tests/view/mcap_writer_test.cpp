// The MCAP writer's own behaviour; the format itself is checked by an
// independent reader (mcap_recording_test.mjs, @mcap/core).
#include "edgevio/view/mcap_writer.h"

#include <gtest/gtest.h>

#include "common/test_support.h"
#include "edgevio/common/error.h"

namespace edgevio::view {
namespace {

TEST(McapWriter, AFolderThatCannotBeWrittenIsAnErrorNamingThePath) {
  test::expectInputError([] { McapWriter w("/nonexistent/folder/run.mcap"); }, {"/nonexistent/folder/run.mcap", "cannot write"});
}

TEST(McapWriter, StartsAndEndsWithTheMagicAndCountsMessagesPerChannel) {
  const test::TempDir dir;
  const std::string path = dir.file("x.mcap");
  {
    McapWriter w(path);
    const std::uint16_t s = w.addSchema("s", "jsonschema", "{}");
    const std::uint16_t a = w.addChannel(s, "/a", "json"), b = w.addChannel(s, "/b", "json");
    EXPECT_NE(a, b);
    w.write(a, 1, "{}");
    w.write(a, 2, "{}");
    w.write(b, 2, "{}");
    EXPECT_EQ(w.messages(a), 2u);
    EXPECT_EQ(w.messages(b), 1u);
    EXPECT_EQ(w.messages(99), 0u);
  }  // the destructor closes the file
  const std::string bytes = test::readFile(path);
  const std::string magic("\x89MCAP0\r\n", 8);
  ASSERT_GT(bytes.size(), 2 * magic.size());
  EXPECT_EQ(bytes.substr(0, 8), magic);
  EXPECT_EQ(bytes.substr(bytes.size() - 8), magic);
}

}  // namespace
}  // namespace edgevio::view
