#include "edgevio/view/mcap_writer.h"

#include <algorithm>

#include "edgevio/common/error.h"

namespace edgevio::view {

namespace {

// The spec's record opcodes.
enum Opcode : std::uint8_t {
  kHeader = 0x01,
  kFooter = 0x02,
  kSchema = 0x03,
  kChannel = 0x04,
  kMessage = 0x05,
  kStatistics = 0x0B,
  kDataEnd = 0x0F,
};

constexpr char kMagic[] = {'\x89', 'M', 'C', 'A', 'P', '0', '\r', '\n'};

/// Little-endian primitives, strings and byte arrays as the spec lays them out.
struct Bytes {
  std::string s;
  template <class T>
  Bytes& le(T v) {
    for (std::size_t i = 0; i < sizeof(T); ++i) s += static_cast<char>((static_cast<std::uint64_t>(v) >> (8 * i)) & 0xFF);
    return *this;
  }
  Bytes& u8(std::uint8_t v) { return le(v); }
  Bytes& u16(std::uint16_t v) { return le(v); }
  Bytes& u32(std::uint32_t v) { return le(v); }
  Bytes& u64(std::uint64_t v) { return le(v); }
  /// String and Bytes: a u32 length, then the bytes.
  Bytes& str(const std::string& v) {
    u32(static_cast<std::uint32_t>(v.size()));
    s += v;
    return *this;
  }
  Bytes& raw(const std::string& v) {
    s += v;
    return *this;
  }
};

}  // namespace

McapWriter::McapWriter(const std::string& path) : path_(path), out_(path, std::ios::binary) {
  if (!out_) throw InputError(path, 0, "cannot write the MCAP recording here");
  out_.write(kMagic, sizeof kMagic);
  offset_ = sizeof kMagic;
  record(kHeader, Bytes().str("").str("edgevio").s);
}

McapWriter::~McapWriter() {
  try {
    close();
  } catch (...) {
    // A destructor must not throw; close() reports a failed write when called directly.
  }
}

void McapWriter::record(std::uint8_t opcode, const std::string& content) {
  const std::string head = Bytes().u8(opcode).u64(content.size()).s;
  out_.write(head.data(), static_cast<std::streamsize>(head.size()));
  out_.write(content.data(), static_cast<std::streamsize>(content.size()));
  offset_ += head.size() + content.size();
}

std::string McapWriter::schemaRecord(const Schema& s) { return Bytes().u16(s.id).str(s.name).str(s.encoding).str(s.data).s; }

std::string McapWriter::channelRecord(const Channel& c) {
  return Bytes().u16(c.id).u16(c.schema_id).str(c.topic).str(c.message_encoding).u32(0).s;  // no metadata: an empty map
}

std::uint16_t McapWriter::addSchema(const std::string& name, const std::string& encoding, const std::string& data) {
  schemas_.push_back({static_cast<std::uint16_t>(schemas_.size() + 1), name, encoding, data});
  record(kSchema, schemaRecord(schemas_.back()));
  return schemas_.back().id;
}

std::uint16_t McapWriter::addChannel(std::uint16_t schema_id, const std::string& topic, const std::string& message_encoding) {
  channels_.push_back({static_cast<std::uint16_t>(channels_.size() + 1), schema_id, topic, message_encoding});
  record(kChannel, channelRecord(channels_.back()));
  message_counts_[channels_.back().id] = 0;
  return channels_.back().id;
}

void McapWriter::write(std::uint16_t channel_id, std::uint64_t log_time_ns, const std::string& data) {
  const std::uint64_t sequence = message_counts_[channel_id]++;
  record(kMessage, Bytes().u16(channel_id).u32(static_cast<std::uint32_t>(sequence)).u64(log_time_ns).u64(log_time_ns).raw(data).s);
  start_ns_ = message_count_ == 0 ? log_time_ns : std::min(start_ns_, log_time_ns);
  end_ns_ = std::max(end_ns_, log_time_ns);
  ++message_count_;
}

std::uint64_t McapWriter::messages(std::uint16_t channel_id) const {
  const auto it = message_counts_.find(channel_id);
  return it == message_counts_.end() ? 0 : it->second;
}

void McapWriter::close() {
  if (closed_) return;
  closed_ = true;
  record(kDataEnd, Bytes().u32(0).s);
  const std::uint64_t summary_start = offset_;
  for (const Schema& s : schemas_) record(kSchema, schemaRecord(s));
  for (const Channel& c : channels_) record(kChannel, channelRecord(c));
  Bytes counts;
  for (const auto& [id, n] : message_counts_) counts.u16(id).u64(n);
  record(kStatistics, Bytes()
                          .u64(message_count_)
                          .u16(static_cast<std::uint16_t>(schemas_.size()))
                          .u32(static_cast<std::uint32_t>(channels_.size()))
                          .u32(0)  // attachments
                          .u32(0)  // metadata
                          .u32(0)  // chunks
                          .u64(start_ns_)
                          .u64(end_ns_)
                          .str(counts.s)  // a map: its byte length, then the entries
                          .s);
  record(kFooter, Bytes().u64(summary_start).u64(0).u32(0).s);  // no summary offset section, no CRC
  out_.write(kMagic, sizeof kMagic);
  out_.close();
  if (!out_) throw InputError(path_, 0, "cannot finish the MCAP recording (disk full?)");
}

}  // namespace edgevio::view
