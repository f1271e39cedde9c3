#pragma once
// An MCAP file writer (the format Foxglove and Lichtblick open), written
// from the specification (mcap.dev/spec, major version 0):
//   <magic> Header [Schema | Channel | Message ...] DataEnd
//   <summary: Schema ... Channel ... Statistics> Footer <magic>
// Every record is <opcode u8><length u64><content>, little-endian; strings
// and byte arrays are prefixed by a u32 length, maps by their u32 byte
// length. Messages are written unchunked as they come, so a file cut short
// by a crash still holds everything before the cut; the summary (schemas,
// channels and statistics) makes a finished file's contents known without
// reading it through. No CRCs (0 means "not computed" in the spec).
#include <cstdint>
#include <fstream>
#include <map>
#include <string>
#include <vector>

namespace edgevio::view {

class McapWriter {
 public:
  /// Opens `path` and writes the magic and the Header (profile "", library
  /// "edgevio"). Throws InputError when the file cannot be written.
  explicit McapWriter(const std::string& path);
  ~McapWriter();
  McapWriter(const McapWriter&) = delete;
  McapWriter& operator=(const McapWriter&) = delete;

  /// A schema (e.g. encoding "jsonschema"); returns its id (from 1).
  std::uint16_t addSchema(const std::string& name, const std::string& encoding, const std::string& data);
  /// A channel on `topic` whose messages follow `schema_id` (e.g. message encoding "json"); returns its id.
  std::uint16_t addChannel(std::uint16_t schema_id, const std::string& topic, const std::string& message_encoding);
  /// One message; `log_time_ns` is also its publish time.
  void write(std::uint16_t channel_id, std::uint64_t log_time_ns, const std::string& data);
  /// Writes DataEnd, the summary, the Footer and the closing magic. Called by the destructor if not before.
  void close();

  std::uint64_t messages(std::uint16_t channel_id) const;

 private:
  struct Schema {
    std::uint16_t id;
    std::string name, encoding, data;
  };
  struct Channel {
    std::uint16_t id, schema_id;
    std::string topic, message_encoding;
  };
  void record(std::uint8_t opcode, const std::string& content);
  static std::string schemaRecord(const Schema& s);
  static std::string channelRecord(const Channel& c);

  std::string path_;
  std::ofstream out_;
  std::uint64_t offset_ = 0;
  std::vector<Schema> schemas_;
  std::vector<Channel> channels_;
  std::map<std::uint16_t, std::uint64_t> message_counts_;
  std::uint64_t message_count_ = 0, start_ns_ = 0, end_ns_ = 0;
  bool closed_ = false;
};

}  // namespace edgevio::view
