#pragma once
// Writes ROS 1 bags (format 2.0, see io/rosbag.h): messages are gathered
// into chunks of about `chunk_bytes`, each written whole (uncompressed, bz2
// or lz4) and followed by its index records; closing writes the connection
// and chunk-info records and the bag header's index position. Messages must
// be written in time order.
#include <cstdint>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "edgevio/common/options.h"

namespace edgevio::io {

enum class BagCompression { kNone, kBz2, kLz4 };
inline constexpr options::Choice<BagCompression> kBagCompressionChoices[] = {
    {BagCompression::kNone, "none", "uncompressed chunks (as EuRoC's bags)"},
    {BagCompression::kBz2, "bz2", "bzip2 chunks: small, slow to read"},
    {BagCompression::kLz4, "lz4", "lz4 chunks: fast to read"}};

class RosbagWriter {
 public:
  /// Throws InputError when the file cannot be written.
  RosbagWriter(const std::string& path, BagCompression compression, std::size_t chunk_bytes = 768 * 1024);
  ~RosbagWriter();  ///< closes the bag if close() was not called
  RosbagWriter(const RosbagWriter&) = delete;
  RosbagWriter& operator=(const RosbagWriter&) = delete;

  /// A topic of a message type (io/ros_messages.h names the types); returns its connection id.
  std::uint32_t addConnection(const std::string& topic, const std::string& type);
  void write(std::uint32_t connection, std::int64_t time_ns, const std::vector<std::uint8_t>& message);
  /// Writes the last chunk and the index; throws InputError when writing failed.
  void close();

 private:
  struct Connection {
    std::string topic, type;
    bool written = false;  ///< its record is in a chunk already
  };
  void flushChunk();
  void writeRecord(const std::vector<std::uint8_t>& header, const std::vector<std::uint8_t>& data);
  std::vector<std::uint8_t> connectionData(const Connection& c) const;

  std::string path_;
  std::FILE* file_ = nullptr;
  BagCompression compression_;
  std::size_t chunk_bytes_;
  std::vector<Connection> connections_;
  std::vector<std::uint8_t> chunk_;  ///< the open chunk's records, uncompressed
  /// Per connection in the open chunk: (time, offset) of its messages.
  std::map<std::uint32_t, std::vector<std::pair<std::int64_t, std::uint32_t>>> chunk_index_;
  std::int64_t chunk_start_ = 0, chunk_end_ = 0;
  struct ChunkInfo {
    std::uint64_t pos;
    std::int64_t start, end;
    std::map<std::uint32_t, std::uint32_t> counts;
  };
  std::vector<ChunkInfo> chunk_infos_;
  bool closed_ = false;
};

}  // namespace edgevio::io
