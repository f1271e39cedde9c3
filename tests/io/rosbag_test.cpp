// ROS 1 bags: what the writer writes the reader reads back, in every
// compression; bags cut short, killed before their index or damaged at any
// byte give a warning or an InputError naming the file, never a crash.
#include "edgevio/io/rosbag.h"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>

#include "common/test_support.h"
#include "edgevio/common/error.h"
#include "edgevio/io/ros_messages.h"
#include "edgevio/io/rosbag_writer.h"

namespace edgevio::io {
namespace {

using test::TempDir;

struct Written {
  std::uint32_t connection;
  std::int64_t time_ns;
  std::vector<std::uint8_t> data;
};

/// 300 messages on three topics, of 1 byte to 3 kB of seeded noise, in chunks of 4 kB.
std::vector<Written> writeBag(const std::string& path, BagCompression compression) {
  RosbagWriter bag(path, compression, 4096);
  const std::uint32_t ids[3] = {bag.addConnection("/cam0/image_raw", ros::kImage), bag.addConnection("/imu0", ros::kImu),
                                bag.addConnection("/gt", ros::kPoseStamped)};
  std::mt19937 rng(7);
  std::vector<Written> out;
  for (int k = 0; k < 300; ++k) {
    Written w{ids[k % 3], 1403715273000000000LL + 5000000LL * k, std::vector<std::uint8_t>(1 + rng() % 3000)};
    for (auto& b : w.data) b = static_cast<std::uint8_t>(rng());
    bag.write(w.connection, w.time_ns, w.data);
    out.push_back(std::move(w));
  }
  bag.close();
  return out;
}

/// Every message the reader indexes, read, in file order.
std::vector<Written> readAll(RosbagReader& reader) {
  std::vector<Written> out;
  for (const BagMessageRef& ref : reader.messagesInFileOrder()) out.push_back({ref.connection, ref.record_time_ns, reader.read(ref)});
  return out;
}

void expectSameMessages(const std::vector<Written>& got, const std::vector<Written>& written, std::size_t count) {
  ASSERT_EQ(got.size(), count);
  for (std::size_t k = 0; k < count; ++k) {
    EXPECT_EQ(got[k].connection, written[k].connection) << k;
    EXPECT_EQ(got[k].time_ns, written[k].time_ns) << k;
    EXPECT_EQ(got[k].data, written[k].data) << k;
  }
}

std::uint64_t indexPos(const std::string& path) {
  const std::string bytes = test::readFile(path);
  const std::size_t at = bytes.find("index_pos=");
  std::uint64_t v = 0;
  std::memcpy(&v, bytes.data() + at + 10, 8);
  return v;
}

/// Rewrites the bag as a recorder killed at `size` bytes leaves it: no index position, nothing after `size`.
void killAt(const std::string& path, std::uint64_t size) {
  std::string bytes = test::readFile(path);
  const std::size_t at = bytes.find("index_pos=");
  std::memset(&bytes[at + 10], 0, 8);
  bytes.resize(size);
  std::ofstream(path, std::ios::binary) << bytes;
}

bool anyWarning(const RosbagReader& r, const std::string& fragment) {
  for (const auto& w : r.warnings())
    if (w.find(fragment) != std::string::npos && w.find(r.path()) != std::string::npos) return true;
  return false;
}

TEST(Rosbag, WhatIsWrittenIsReadBackInEveryCompression) {
  for (BagCompression c : {BagCompression::kNone, BagCompression::kBz2, BagCompression::kLz4}) {
    TempDir dir;
    const std::vector<Written> written = writeBag(dir.file("a.bag"), c);
    ASSERT_TRUE(RosbagReader::looksLikeBag(dir.file("a.bag")));
    RosbagReader reader(dir.file("a.bag"));
    EXPECT_TRUE(reader.warnings().empty());
    ASSERT_EQ(reader.connections().size(), 3u);
    EXPECT_EQ(reader.connections()[1].topic, "/imu0");
    EXPECT_EQ(reader.connections()[1].type, ros::kImu);
    EXPECT_EQ(reader.connections()[1].md5sum, ros::messageType(ros::kImu).md5sum);
    expectSameMessages(readAll(reader), written, written.size());
    // A prefix: the header's stamp without reading the rest.
    const BagMessageRef last = reader.messagesInFileOrder().back();
    const std::vector<std::uint8_t> head = reader.read(last, 12);
    EXPECT_EQ(head, std::vector<std::uint8_t>(written.back().data.begin(), written.back().data.begin() + 12));
  }
}

TEST(Rosbag, AKilledRecordingIsReadUpToItsLastCompleteChunk) {
  for (BagCompression c : {BagCompression::kNone, BagCompression::kLz4}) {
    TempDir dir;
    const std::string path = dir.file("killed.bag");
    const std::vector<Written> written = writeBag(path, c);
    // Killed after its last chunk: no index, every message is there.
    killAt(path, indexPos(path));
    {
      RosbagReader reader(path);
      EXPECT_TRUE(anyWarning(reader, "no index")) << "no warning for the missing index";
      expectSameMessages(readAll(reader), written, written.size());
    }
    // Killed inside a chunk: the messages of the chunks before it.
    killAt(path, std::filesystem::file_size(path) / 2);
    RosbagReader reader(path);
    EXPECT_TRUE(anyWarning(reader, "ends inside a record"));
    const std::vector<Written> got = readAll(reader);
    EXPECT_GT(got.size(), 50u);
    EXPECT_LT(got.size(), 200u);
    expectSameMessages(got, written, got.size());
  }
}

TEST(Rosbag, WhatIsNotABagIsAnErrorNamingTheFile) {
  TempDir dir;
  const auto expectError = [](const std::string& path, const std::string& fragment) {
    test::expectInputError([&] { RosbagReader r(path); }, {path, fragment});
  };
  expectError(dir.file("missing.bag"), "cannot open");
  expectError(dir.write("empty.bag", ""), "not a ROS 1 bag");
  expectError(dir.write("v1.bag", "#ROSRECORD V1.2\n"), "not a ROS 1 bag");
  expectError(dir.write("cut.bag", "#ROSBAG V2.0\n\x40"), "header record");
  EXPECT_FALSE(RosbagReader::looksLikeBag(dir.file("empty.bag")));
}

/// Opens the bag and reads every message; true when that worked, false for an InputError.
bool readsOrSaysWhy(const std::string& path) {
  try {
    RosbagReader reader(path);
    readAll(reader);
    return true;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    return false;
  }
}

TEST(Rosbag, ABagDamagedAtAnyByteReadsOrSaysWhy) {
  // A byte changed, in the header, a chunk, the index or a message, in each
  // compression: a read, or an InputError, never anything else (the
  // sanitizer build runs this too).
  for (BagCompression c : {BagCompression::kNone, BagCompression::kBz2, BagCompression::kLz4}) {
    TempDir dir;
    writeBag(dir.file("good.bag"), c);
    const std::string good = test::readFile(dir.file("good.bag"));
    std::mt19937 rng(11);
    int errors = 0;
    for (int trial = 0; trial < 60; ++trial) {
      std::string bad = good;
      // Half the trials in the first 5 kB (bag header, first chunk's headers), half anywhere.
      const std::size_t at = (trial % 2 ? rng() % good.size() : rng() % 5000);
      bad[at] = static_cast<char>(trial % 3 == 0 ? 0xff : static_cast<int>(rng()));
      std::ofstream(dir.file("bad.bag"), std::ios::binary) << bad;
      errors += !readsOrSaysWhy(dir.file("bad.bag"));
    }
    EXPECT_GT(errors, 0) << "no damage was noticed";
  }
}

}  // namespace
}  // namespace edgevio::io
