// Base64 against the test vectors of RFC 4648, section 10.
#include "edgevio/common/base64.h"

#include <gtest/gtest.h>

namespace edgevio {
namespace {

std::string encode(const std::string& s) { return base64(reinterpret_cast<const std::uint8_t*>(s.data()), s.size()); }

TEST(Base64, MatchesTheRfc4648TestVectors) {
  EXPECT_EQ(encode(""), "");
  EXPECT_EQ(encode("f"), "Zg==");
  EXPECT_EQ(encode("fo"), "Zm8=");
  EXPECT_EQ(encode("foo"), "Zm9v");
  EXPECT_EQ(encode("foob"), "Zm9vYg==");
  EXPECT_EQ(encode("fooba"), "Zm9vYmE=");
  EXPECT_EQ(encode("foobar"), "Zm9vYmFy");
}

TEST(Base64, UsesEveryCharacterOfTheAlphabetForHighBytes) {
  const std::uint8_t bytes[] = {0xFB, 0xFF, 0xBF, 0x00};
  EXPECT_EQ(base64(bytes, 3), "+/+/");
  EXPECT_EQ(base64(bytes, 4), "+/+/AA==");
}

}  // namespace
}  // namespace edgevio
