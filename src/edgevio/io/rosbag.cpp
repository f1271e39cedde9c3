#include "edgevio/io/rosbag.h"

#include <bzlib.h>
#include <lz4frame.h>

#include <algorithm>
#include <cstring>
#include <map>

#include "edgevio/common/error.h"

namespace edgevio::io {

namespace {

constexpr char kMagic[] = "#ROSBAG V2.0\n";
constexpr std::size_t kMagicLength = sizeof(kMagic) - 1;
// No header or chunk is larger than this in any bag a recorder writes; a
// larger length is a damaged file, not an allocation to attempt.
constexpr std::uint32_t kMaxHeader = 1u << 20;
constexpr std::uint32_t kMaxData = 1u << 30;

enum Op : std::uint8_t { kMessageData = 0x02, kBagHeader = 0x03, kIndexData = 0x04, kChunk = 0x05, kChunkInfo = 0x06, kConnection = 0x07 };

std::uint32_t u32(const std::uint8_t* p) { return p[0] | (p[1] << 8) | (p[2] << 16) | (static_cast<std::uint32_t>(p[3]) << 24); }
std::uint64_t u64(const std::uint8_t* p) { return u32(p) | (static_cast<std::uint64_t>(u32(p + 4)) << 32); }
std::int64_t timeNs(const std::uint8_t* p) {
  return static_cast<std::int64_t>(u32(p)) * 1000000000LL + static_cast<std::int64_t>(u32(p + 4));
}

/// The name=value fields of a record header.
using Fields = std::map<std::string, std::string>;

bool parseFields(const std::uint8_t* p, std::size_t n, Fields* out) {
  std::size_t i = 0;
  while (i < n) {
    if (n - i < 4) return false;
    const std::uint32_t len = u32(p + i);
    i += 4;
    if (len > n - i) return false;
    const std::string field(reinterpret_cast<const char*>(p + i), len);
    const std::size_t eq = field.find('=');
    if (eq == std::string::npos) return false;
    (*out)[field.substr(0, eq)] = field.substr(eq + 1);
    i += len;
  }
  return true;
}

std::string atByte(std::uint64_t pos) { return "byte " + std::to_string(pos); }

/// A record inside a decompressed chunk: its header fields and where its data lies.
struct ChunkRecord {
  Fields fields;
  std::size_t data_at = 0;
  std::uint32_t data_len = 0;
};

/// The record at `off` of a chunk's bytes (its fields parsed when `with_fields`);
/// false when it runs past them or its header does not parse.
bool chunkRecordAt(const std::vector<std::uint8_t>& data, std::size_t off, bool with_fields, ChunkRecord* r) {
  if (off + 8 > data.size()) return false;
  const std::uint32_t header_len = u32(&data[off]);
  if (header_len > data.size() - off - 8) return false;
  r->fields.clear();
  if (with_fields && !parseFields(&data[off + 4], header_len, &r->fields)) return false;
  r->data_len = u32(&data[off + 4 + header_len]);
  r->data_at = off + 8 + header_len;
  return r->data_len <= data.size() - r->data_at;
}

}  // namespace

struct RosbagReader::Record {
  std::uint64_t pos = 0, data_pos = 0, end = 0;  ///< file offsets
  std::uint32_t data_len = 0;
  Fields fields;
  std::vector<std::uint8_t> data;
  int op() const {
    const auto it = fields.find("op");
    return it == fields.end() || it->second.size() != 1 ? -1 : static_cast<std::uint8_t>(it->second[0]);
  }
  /// A fixed-size field; false when absent or of another size.
  bool field(const char* name, std::size_t size, const std::uint8_t** value) const {
    const auto it = fields.find(name);
    if (it == fields.end() || it->second.size() != size) return false;
    *value = reinterpret_cast<const std::uint8_t*>(it->second.data());
    return true;
  }
};

bool RosbagReader::looksLikeBag(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  char head[kMagicLength] = {};
  return f.read(head, kMagicLength) && std::memcmp(head, kMagic, kMagicLength) == 0;
}

RosbagReader::RosbagReader(const std::string& path) : path_(path), in_(path, std::ios::binary) {
  if (!in_) throw InputError(path, 0, "cannot open the bag (check the path and permissions)");
  in_.seekg(0, std::ios::end);
  size_ = static_cast<std::uint64_t>(in_.tellg());
  char head[kMagicLength] = {};
  in_.seekg(0);
  if (!in_.read(head, kMagicLength) || std::memcmp(head, kMagic, kMagicLength) != 0)
    throw InputError(path, 0, "not a ROS 1 bag of format 2.0 (it does not start with \"#ROSBAG V2.0\")");
  Record header;
  if (!readRecord(kMagicLength, &header, 0) || header.op() != kBagHeader)
    throw InputError(path, 0, "the bag header record is missing or damaged at " + atByte(kMagicLength));
  const std::uint8_t *index_pos = nullptr, *chunk_count = nullptr;
  if (!header.field("index_pos", 8, &index_pos) || !header.field("chunk_count", 4, &chunk_count))
    throw InputError(path, 0, "the bag header lacks index_pos or chunk_count");
  if (u64(index_pos) == 0 || u64(index_pos) >= size_) {
    warnings_.push_back(path + ": the bag has no index (a recording that was killed?): its chunks were scanned");
    scanWithoutIndex(header.end);
  } else {
    readIndex(u64(index_pos), u32(chunk_count));
  }
  // A damaged index can name a connection the bag never describes: such a
  // message has no topic or type to be read as.
  const auto undescribed = std::remove_if(index_.begin(), index_.end(),
                                          [this](const BagMessageRef& ref) { return connection(ref.connection) == nullptr; });
  if (undescribed != index_.end()) {
    warnings_.push_back(path + ": " + std::to_string(index_.end() - undescribed) +
                        " messages of connections the bag does not describe were left out (a damaged index?)");
    index_.erase(undescribed, index_.end());
  }
  std::stable_sort(index_.begin(), index_.end(),
                   [](const BagMessageRef& a, const BagMessageRef& b) { return a.record_time_ns < b.record_time_ns; });
}

RosbagReader::~RosbagReader() = default;

bool RosbagReader::readRecord(std::uint64_t pos, Record* r, std::size_t max_data) {
  r->pos = pos;
  std::uint8_t len[4];
  if (pos + 4 > size_) return false;
  in_.clear();
  in_.seekg(static_cast<std::streamoff>(pos));
  if (!in_.read(reinterpret_cast<char*>(len), 4)) return false;
  const std::uint32_t header_len = u32(len);
  if (header_len > kMaxHeader || pos + 8 + header_len > size_) return false;
  std::vector<std::uint8_t> header(header_len);
  if (!in_.read(reinterpret_cast<char*>(header.data()), header_len) || !in_.read(reinterpret_cast<char*>(len), 4)) return false;
  r->fields.clear();
  if (!parseFields(header.data(), header.size(), &r->fields)) return false;
  r->data_len = u32(len);
  r->data_pos = pos + 8 + header_len;
  r->end = r->data_pos + r->data_len;
  if (r->data_len > kMaxData || r->end > size_) return false;
  r->data.resize(std::min<std::size_t>(r->data_len, max_data));
  return r->data.empty() || static_cast<bool>(in_.read(reinterpret_cast<char*>(r->data.data()), static_cast<std::streamsize>(r->data.size())));
}

void RosbagReader::addConnection(std::uint32_t id, const std::string& topic, const std::vector<std::uint8_t>& header) {
  for (const BagConnection& c : connections_)
    if (c.id == id) return;
  Fields f;
  parseFields(header.data(), header.size(), &f);
  connections_.push_back({id, topic, f["type"], f["md5sum"]});
}

void RosbagReader::readIndex(std::uint64_t index_pos, std::uint32_t chunk_count) {
  // Connection records, then one chunk info record per chunk.
  std::uint64_t pos = index_pos;
  std::vector<std::uint64_t> chunk_positions;
  Record r;
  while (pos < size_) {
    if (!readRecord(pos, &r, SIZE_MAX))
      throw InputError(path_, 0, "the bag's index is damaged at " + atByte(pos) + " (index_pos " + std::to_string(index_pos) + ")");
    const std::uint8_t* conn = nullptr;
    const std::uint8_t* chunk_pos = nullptr;
    if (r.op() == kConnection && r.field("conn", 4, &conn)) addConnection(u32(conn), r.fields["topic"], r.data);
    if (r.op() == kChunkInfo && r.field("chunk_pos", 8, &chunk_pos)) chunk_positions.push_back(u64(chunk_pos));
    pos = r.end;
  }
  if (chunk_positions.size() != chunk_count)
    warnings_.push_back(path_ + ": the bag header says " + std::to_string(chunk_count) + " chunks, its index lists " +
                        std::to_string(chunk_positions.size()));
  for (const std::uint64_t chunk_pos : chunk_positions) readChunkIndex(chunk_pos);
}

void RosbagReader::readChunkIndex(std::uint64_t chunk_pos) {
  // The chunk record, then its index data records (one per connection in it).
  Record chunk;
  const std::uint8_t* size = nullptr;
  if (!readRecord(chunk_pos, &chunk, 0) || chunk.op() != kChunk || !chunk.field("size", 4, &size))
    throw InputError(path_, 0, "no chunk at " + atByte(chunk_pos) + ", where the index points");
  const auto chunk_index = static_cast<std::uint32_t>(chunks_.size());
  chunks_.push_back({chunk.data_pos, chunk.data_len, u32(size), chunk.fields["compression"]});
  std::uint64_t pos = chunk.end;
  Record r;
  while (pos < size_ && readRecord(pos, &r, SIZE_MAX) && r.op() == kIndexData) {
    const std::uint8_t *conn = nullptr, *count = nullptr;
    if (!r.field("conn", 4, &conn) || !r.field("count", 4, &count) || r.data.size() < 12ull * u32(count))
      throw InputError(path_, 0, "damaged index data record at " + atByte(pos));
    for (std::uint32_t k = 0; k < u32(count); ++k)
      index_.push_back({u32(conn), timeNs(&r.data[12 * k]), chunk_index, u32(&r.data[12 * k + 8])});
    pos = r.end;
  }
}

void RosbagReader::scanWithoutIndex(std::uint64_t first_record) {
  std::uint64_t pos = first_record;
  Record r;
  while (pos < size_) {
    if (!readRecord(pos, &r, 0)) {
      warnings_.push_back(path_ + ": the bag ends inside a record at " + atByte(pos) + "; the last " +
                          std::to_string(size_ - pos) + " bytes are ignored");
      break;
    }
    const std::uint8_t* size = nullptr;
    if (r.op() == kChunk && r.field("size", 4, &size)) {
      // Index the chunk's own records: connections and messages.
      const auto chunk_index = static_cast<std::uint32_t>(chunks_.size());
      chunks_.push_back({r.data_pos, r.data_len, u32(size), r.fields["compression"]});
      const std::vector<std::uint8_t>& data = chunkData(chunk_index);
      std::size_t off = 0;
      ChunkRecord rec;
      while (chunkRecordAt(data, off, true, &rec)) {
        Fields& f = rec.fields;
        const std::size_t data_at = rec.data_at, data_len = rec.data_len;
        const int op = f["op"].size() == 1 ? static_cast<std::uint8_t>(f["op"][0]) : -1;
        if (op == kConnection && f["conn"].size() == 4)
          addConnection(u32(reinterpret_cast<const std::uint8_t*>(f["conn"].data())), f["topic"],
                        std::vector<std::uint8_t>(data.begin() + static_cast<long>(data_at), data.begin() + static_cast<long>(data_at + data_len)));
        if (op == kMessageData && f["conn"].size() == 4 && f["time"].size() == 8)
          index_.push_back({u32(reinterpret_cast<const std::uint8_t*>(f["conn"].data())),
                            timeNs(reinterpret_cast<const std::uint8_t*>(f["time"].data())), chunk_index, static_cast<std::uint32_t>(off)});
        off = data_at + data_len;
      }
    }
    pos = r.end;
  }
}

const std::vector<std::uint8_t>& RosbagReader::chunkData(std::uint32_t chunk) {
  if (cache_[0].chunk == chunk) return cache_[0].data;
  if (cache_[1].chunk == chunk) return cache_[1].data;
  std::swap(cache_[0], cache_[1]);  // the older one makes room
  std::vector<std::uint8_t>& out = cache_[0].data;
  cache_[0].chunk = UINT32_MAX;
  const Chunk& c = chunks_.at(chunk);
  std::vector<std::uint8_t> raw(c.data_len);
  in_.clear();
  in_.seekg(static_cast<std::streamoff>(c.data_pos));
  if (!in_.read(reinterpret_cast<char*>(raw.data()), c.data_len))
    throw InputError(path_, 0, "cannot read the chunk at " + atByte(c.data_pos));
  const std::string where = "the " + c.compression + " chunk at " + atByte(c.data_pos);
  if (c.size > kMaxData) throw InputError(path_, 0, where + " claims " + std::to_string(c.size) + " bytes uncompressed: damaged");
  if (c.compression == "none") {
    out = std::move(raw);
  } else if (c.compression == "bz2") {
    out.assign(c.size, 0);
    unsigned int out_len = c.size;
    const int rc = BZ2_bzBuffToBuffDecompress(reinterpret_cast<char*>(out.data()), &out_len, reinterpret_cast<char*>(raw.data()),
                                              c.data_len, 0, 0);
    if (rc != BZ_OK || out_len != c.size) throw InputError(path_, 0, where + " does not decompress (bzip2 error " + std::to_string(rc) + ")");
  } else if (c.compression == "lz4") {
    out.assign(c.size, 0);
    LZ4F_dctx* ctx = nullptr;
    if (LZ4F_isError(LZ4F_createDecompressionContext(&ctx, LZ4F_VERSION))) throw InputError(path_, 0, "lz4 is unavailable");
    std::size_t out_len = c.size, in_len = raw.size();
    const std::size_t rc = LZ4F_decompress(ctx, out.data(), &out_len, raw.data(), &in_len, nullptr);
    LZ4F_freeDecompressionContext(ctx);
    if (LZ4F_isError(rc) || out_len != c.size) throw InputError(path_, 0, where + " does not decompress (lz4)");
  } else {
    throw InputError(path_, 0, where + ": unknown compression '" + c.compression + "' (expected none, bz2 or lz4)");
  }
  cache_[0].chunk = chunk;
  return out;
}

const BagConnection* RosbagReader::connection(std::uint32_t id) const {
  for (const BagConnection& c : connections_)
    if (c.id == id) return &c;
  return nullptr;
}

std::vector<BagMessageRef> RosbagReader::messagesInFileOrder() const {
  std::vector<BagMessageRef> out = index_;
  std::sort(out.begin(), out.end(), [](const BagMessageRef& a, const BagMessageRef& b) {
    return a.chunk != b.chunk ? a.chunk < b.chunk : a.offset < b.offset;
  });
  return out;
}

std::vector<std::uint8_t> RosbagReader::read(const BagMessageRef& ref, std::size_t max_bytes) {
  const Chunk& c = chunks_.at(ref.chunk);
  const std::string where = "the message record at offset " + std::to_string(ref.offset) + " of the chunk at " + atByte(c.data_pos);
  if (c.compression == "none") {
    // Straight from the file: an uncompressed chunk's records are in place.
    Record r;
    if (ref.offset >= c.data_len || !readRecord(c.data_pos + ref.offset, &r, max_bytes) || r.end > c.data_pos + c.data_len ||
        r.op() != kMessageData)
      throw InputError(path_, 0, where + " is damaged");
    return std::move(r.data);
  }
  const std::vector<std::uint8_t>& data = chunkData(ref.chunk);
  if (std::size_t{ref.offset} + 8 > data.size()) throw InputError(path_, 0, where + " lies outside the chunk");
  ChunkRecord rec;
  if (!chunkRecordAt(data, ref.offset, false, &rec)) throw InputError(path_, 0, where + " is damaged");
  const std::size_t n = std::min<std::size_t>(rec.data_len, max_bytes);
  return std::vector<std::uint8_t>(data.begin() + static_cast<long>(rec.data_at), data.begin() + static_cast<long>(rec.data_at + n));
}

}  // namespace edgevio::io
