#include "edgevio/io/rosbag_writer.h"

#include <bzlib.h>
#include <lz4frame.h>

#include "edgevio/common/error.h"
#include "edgevio/io/ros_messages.h"

namespace edgevio::io {

namespace {

constexpr char kMagic[] = "#ROSBAG V2.0\n";
// The bag header record is padded to this many bytes, so that its index
// position can be written in place when the bag is closed (the format's rule).
constexpr std::size_t kBagHeaderBytes = 4096;

using Bytes = std::vector<std::uint8_t>;

void putU32(Bytes* b, std::uint32_t v) {
  for (int k = 0; k < 4; ++k) b->push_back(static_cast<std::uint8_t>(v >> (8 * k)));
}
void putTime(Bytes* b, std::int64_t ns) {
  putU32(b, static_cast<std::uint32_t>(ns / 1000000000LL));
  putU32(b, static_cast<std::uint32_t>(ns % 1000000000LL));
}
std::string u32Field(std::uint32_t v) {
  Bytes b;
  putU32(&b, v);
  return std::string(b.begin(), b.end());
}
std::string u64Field(std::uint64_t v) { return u32Field(static_cast<std::uint32_t>(v)) + u32Field(static_cast<std::uint32_t>(v >> 32)); }
std::string timeField(std::int64_t ns) {
  Bytes b;
  putTime(&b, ns);
  return std::string(b.begin(), b.end());
}

/// A record header: name=value fields, each preceded by its length.
Bytes header(const std::vector<std::pair<std::string, std::string>>& fields) {
  Bytes h;
  for (const auto& [name, value] : fields) {
    putU32(&h, static_cast<std::uint32_t>(name.size() + 1 + value.size()));
    h.insert(h.end(), name.begin(), name.end());
    h.push_back('=');
    h.insert(h.end(), value.begin(), value.end());
  }
  return h;
}

void appendRecord(Bytes* out, const Bytes& head, const Bytes& data) {
  putU32(out, static_cast<std::uint32_t>(head.size()));
  out->insert(out->end(), head.begin(), head.end());
  putU32(out, static_cast<std::uint32_t>(data.size()));
  out->insert(out->end(), data.begin(), data.end());
}

std::string op(std::uint8_t code) { return std::string(1, static_cast<char>(code)); }

Bytes compress(const Bytes& in, BagCompression c, const std::string& path) {
  if (c == BagCompression::kNone) return in;
  Bytes out;
  if (c == BagCompression::kBz2) {
    out.resize(in.size() + in.size() / 100 + 600);  // bzip2's documented worst case
    unsigned int len = static_cast<unsigned int>(out.size());
    if (BZ2_bzBuffToBuffCompress(reinterpret_cast<char*>(out.data()), &len, const_cast<char*>(reinterpret_cast<const char*>(in.data())),
                                 static_cast<unsigned int>(in.size()), 9, 0, 0) != BZ_OK)
      throw InputError(path, 0, "bzip2 compression failed");
    out.resize(len);
  } else {
    // ROS's lz4 reader (roslz4) accepts only frames of independent blocks with a content checksum.
    LZ4F_preferences_t prefs{};
    prefs.frameInfo.blockMode = LZ4F_blockIndependent;
    prefs.frameInfo.contentChecksumFlag = LZ4F_contentChecksumEnabled;
    out.resize(LZ4F_compressFrameBound(in.size(), &prefs));
    const std::size_t len = LZ4F_compressFrame(out.data(), out.size(), in.data(), in.size(), &prefs);
    if (LZ4F_isError(len)) throw InputError(path, 0, "lz4 compression failed");
    out.resize(len);
  }
  return out;
}

}  // namespace

RosbagWriter::RosbagWriter(const std::string& path, BagCompression compression, std::size_t chunk_bytes)
    : path_(path), file_(std::fopen(path.c_str(), "wb")), compression_(compression), chunk_bytes_(chunk_bytes) {
  if (!file_) throw InputError(path, 0, "cannot open the bag for writing (does the folder exist?)");
  std::fwrite(kMagic, 1, sizeof(kMagic) - 1, file_);
  // A placeholder bag header, rewritten by close().
  Bytes placeholder(kBagHeaderBytes, ' ');
  std::fwrite(placeholder.data(), 1, placeholder.size(), file_);
}

RosbagWriter::~RosbagWriter() {
  if (closed_) return;
  try {
    close();
  } catch (const InputError&) {  // a destructor must not throw; close() reports to callers that ask
  }
}

std::uint32_t RosbagWriter::addConnection(const std::string& topic, const std::string& type) {
  connections_.push_back({topic, type});
  return static_cast<std::uint32_t>(connections_.size() - 1);
}

Bytes RosbagWriter::connectionData(const Connection& c) const {
  const ros::MessageType& t = ros::messageType(c.type);
  return header({{"topic", c.topic}, {"type", c.type}, {"md5sum", t.md5sum}, {"message_definition", t.definition}});
}

void RosbagWriter::write(std::uint32_t connection, std::int64_t time_ns, const std::vector<std::uint8_t>& message) {
  Connection& c = connections_.at(connection);
  if (!c.written) {
    appendRecord(&chunk_, header({{"op", op(0x07)}, {"conn", u32Field(connection)}, {"topic", c.topic}}), connectionData(c));
    c.written = true;
  }
  if (chunk_index_.empty()) chunk_start_ = time_ns;
  chunk_end_ = std::max(chunk_end_, time_ns);
  chunk_index_[connection].emplace_back(time_ns, static_cast<std::uint32_t>(chunk_.size()));
  appendRecord(&chunk_, header({{"op", op(0x02)}, {"conn", u32Field(connection)}, {"time", timeField(time_ns)}}), message);
  if (chunk_.size() >= chunk_bytes_) flushChunk();
}

void RosbagWriter::writeRecord(const Bytes& head, const Bytes& data) {
  Bytes r;
  appendRecord(&r, head, data);
  std::fwrite(r.data(), 1, r.size(), file_);
}

void RosbagWriter::flushChunk() {
  if (chunk_index_.empty()) return;
  ChunkInfo info{static_cast<std::uint64_t>(std::ftell(file_)), chunk_start_, chunk_end_, {}};
  const char* names[] = {"none", "bz2", "lz4"};
  writeRecord(header({{"op", op(0x05)}, {"compression", names[static_cast<int>(compression_)]},
                      {"size", u32Field(static_cast<std::uint32_t>(chunk_.size()))}}),
              compress(chunk_, compression_, path_));
  for (const auto& [conn, entries] : chunk_index_) {
    Bytes data;
    for (const auto& [t, offset] : entries) {
      putTime(&data, t);
      putU32(&data, offset);
    }
    writeRecord(header({{"op", op(0x04)}, {"ver", u32Field(1)}, {"conn", u32Field(conn)},
                        {"count", u32Field(static_cast<std::uint32_t>(entries.size()))}}),
                data);
    info.counts[conn] = static_cast<std::uint32_t>(entries.size());
  }
  chunk_infos_.push_back(info);
  chunk_.clear();
  chunk_index_.clear();
  chunk_end_ = 0;
}

void RosbagWriter::close() {
  if (closed_) return;
  closed_ = true;
  flushChunk();
  const auto index_pos = static_cast<std::uint64_t>(std::ftell(file_));
  for (std::uint32_t id = 0; id < connections_.size(); ++id)
    writeRecord(header({{"op", op(0x07)}, {"conn", u32Field(id)}, {"topic", connections_[id].topic}}), connectionData(connections_[id]));
  for (const ChunkInfo& c : chunk_infos_) {
    Bytes data;
    for (const auto& [conn, count] : c.counts) {
      putU32(&data, conn);
      putU32(&data, count);
    }
    writeRecord(header({{"op", op(0x06)}, {"ver", u32Field(1)}, {"chunk_pos", u64Field(c.pos)}, {"start_time", timeField(c.start)},
                        {"end_time", timeField(c.end)}, {"count", u32Field(static_cast<std::uint32_t>(c.counts.size()))}}),
                data);
  }
  // The bag header in its padded place.
  const Bytes head = header({{"op", op(0x03)}, {"index_pos", u64Field(index_pos)},
                             {"conn_count", u32Field(static_cast<std::uint32_t>(connections_.size()))},
                             {"chunk_count", u32Field(static_cast<std::uint32_t>(chunk_infos_.size()))}});
  const Bytes padding(kBagHeaderBytes - 8 - head.size(), ' ');
  std::fseek(file_, sizeof(kMagic) - 1, SEEK_SET);
  writeRecord(head, padding);
  const bool ok = std::ferror(file_) == 0;
  std::fclose(file_);
  file_ = nullptr;
  if (!ok) throw InputError(path_, 0, "writing the bag failed (disk full?)");
}

}  // namespace edgevio::io
