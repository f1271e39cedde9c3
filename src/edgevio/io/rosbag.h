#pragma once
// ROS 1 bags (format 2.0), read from the documented format
// (http://wiki.ros.org/Bags/Format/2.0) without a ROS installation.
//
// A bag is "#ROSBAG V2.0\n" then records, each a header of fields
// (name=value, with an `op` code) and data:
//   0x03 bag header   index_pos, conn_count, chunk_count (padded to 4096 bytes)
//   0x05 chunk        compression (none | bz2 | lz4), size: connection and
//                     message records, compressed together
//   0x04 index data   after each chunk, per connection: (time, offset in the
//                     uncompressed chunk) of its messages there
//   0x07 connection   conn, topic; data: the connection header (type, md5sum, ...)
//   0x02 message data conn, time; data: the serialised message
//   0x06 chunk info   at index_pos, with the connections: chunk_pos, times, counts
// All integers are little-endian; a time is sec (u32) then nsec (u32).
//
// The reader builds an index of every message (connection, record time,
// chunk, offset) from the index records, reading no message data; a bag
// whose index is missing (a recording that was killed) is indexed by
// scanning its chunks, with a warning, up to the last complete one. A
// message's bytes are read on demand; the last two decompressed chunks are kept,
// so messages are best read in index order. Nothing of the bag is held
// beyond that chunk. Errors (InputError) name the file and what was wrong
// at which byte offset; a reader is not shared between threads.
#include <cstdint>
#include <cstddef>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

namespace edgevio::io {

struct BagConnection {
  std::uint32_t id = 0;
  std::string topic, type, md5sum;
};

/// Where one message is.
struct BagMessageRef {
  std::uint32_t connection = 0;  ///< the connection's id (BagConnection::id)
  std::int64_t record_time_ns = 0;  ///< the bag's receive time (the message's own stamp is in its header)
  std::uint32_t chunk = 0;        ///< index into the chunk list
  std::uint32_t offset = 0;       ///< of the message record in the uncompressed chunk
};

class RosbagReader {
 public:
  /// Opens and indexes the bag; throws InputError when it is not one or is damaged beyond use.
  explicit RosbagReader(const std::string& path);
  ~RosbagReader();
  RosbagReader(const RosbagReader&) = delete;
  RosbagReader& operator=(const RosbagReader&) = delete;

  const std::string& path() const { return path_; }
  const std::vector<BagConnection>& connections() const { return connections_; }
  /// The connection of an id (null when there is none).
  const BagConnection* connection(std::uint32_t id) const;
  /// Every message in file order (each chunk once): the cheapest order to read
  /// many of them. Each message's connection is one of connections().
  std::vector<BagMessageRef> messagesInFileOrder() const;
  /// Warnings from opening (a missing index, a truncated end).
  const std::vector<std::string>& warnings() const { return warnings_; }

  /// The serialised message, or its first `max_bytes` (a header's stamp
  /// without the image behind it); throws InputError when its record is damaged.
  std::vector<std::uint8_t> read(const BagMessageRef& ref, std::size_t max_bytes = SIZE_MAX);

  /// Whether a file starts as a ROS 1 bag does.
  static bool looksLikeBag(const std::string& path);

 private:
  struct Chunk {
    std::uint64_t data_pos = 0;   ///< file offset of the (compressed) chunk data
    std::uint32_t data_len = 0;
    std::uint32_t size = 0;       ///< uncompressed size
    std::string compression;
  };
  struct Record;
  /// Reads the record at `pos` and up to `max_data` bytes of its data; false when it is damaged.
  bool readRecord(std::uint64_t pos, Record* r, std::size_t max_data);
  void readIndex(std::uint64_t index_pos, std::uint32_t chunk_count);
  void readChunkIndex(std::uint64_t chunk_pos);
  void scanWithoutIndex(std::uint64_t first_record);
  void addConnection(std::uint32_t id, const std::string& topic, const std::vector<std::uint8_t>& header);
  const std::vector<std::uint8_t>& chunkData(std::uint32_t chunk);

  std::string path_;
  std::ifstream in_;
  std::uint64_t size_ = 0;
  std::vector<BagConnection> connections_;
  std::vector<Chunk> chunks_;
  std::vector<BagMessageRef> index_;
  std::vector<std::string> warnings_;
  /// The two chunks decompressed last: a stereo pair's two images often straddle two chunks.
  struct Cached {
    std::uint32_t chunk = UINT32_MAX;
    std::vector<std::uint8_t> data;
  };
  Cached cache_[2];
};

}  // namespace edgevio::io
