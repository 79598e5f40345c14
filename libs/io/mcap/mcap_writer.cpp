#include "mcap/mcap_writer.hpp"

#include <fcntl.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace wysiwyf::io::mcap {

namespace {

std::uint32_t crc(std::uint32_t running, const std::uint8_t* p, std::size_t n) {
  return static_cast<std::uint32_t>(crc32_z(running, p, n));
}

}  // namespace

Writer::Writer(const std::string& path, WriterOptions options)
    : path_(path), options_(std::move(options)), compressor_(options_.compression, options_.compression_level) {
  fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0) throw std::runtime_error("cannot write '" + path + "': " + std::strerror(errno));
  Bytes head;
  head.put(kMagic, sizeof kMagic);
  const auto at = head.open(kHeader);
  head.str(options_.profile);
  head.str(options_.library);
  head.close(at);
  emit(head);
}

Writer::~Writer() {
  try {
    close();
  } catch (...) {  // (a destructor must not throw; close() reports to callers who call it)
  }
}

void Writer::emit(const Bytes& bytes, bool data_section) {
  std::size_t done = 0;
  while (done < bytes.b.size()) {
    const ssize_t n = ::write(fd_, bytes.b.data() + done, bytes.b.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw std::runtime_error("cannot write '" + path_ + "': " + std::strerror(errno));
    done += static_cast<std::size_t>(n);
  }
  if (data_section) data_crc_ = crc(data_crc_, bytes.b.data(), bytes.b.size());
  offset_ += bytes.b.size();
}

std::uint16_t Writer::add_schema(const std::string& name, const std::string& encoding, const std::string& data) {
  const std::uint16_t id = next_schema_++;
  Bytes r;
  const auto at = r.open(kSchema);
  r.u16(id);
  r.str(name);
  r.str(encoding);
  r.bytes32(reinterpret_cast<const std::uint8_t*>(data.data()), data.size());
  r.close(at);
  emit(r);  // before any chunk that holds its messages
  schemas_.put(r.b.data(), r.b.size());
  return id;
}

std::uint16_t Writer::add_channel(std::uint16_t schema_id, const std::string& topic,
                                  const std::string& message_encoding,
                                  const std::map<std::string, std::string>& metadata) {
  const std::uint16_t id = next_channel_++;
  Bytes r;
  const auto at = r.open(kChannel);
  r.u16(id);
  r.u16(schema_id);
  r.str(topic);
  r.str(message_encoding);
  Bytes map;
  for (const auto& [k, v] : metadata) map.str(k), map.str(v);
  r.bytes32(map.b.data(), map.b.size());
  r.close(at);
  emit(r);
  channels_.put(r.b.data(), r.b.size());
  channel_counts_[id];  // (listed in the statistics even without messages)
  return id;
}

void Writer::write(std::uint16_t channel, std::uint32_t sequence, std::uint64_t log_time, std::uint64_t publish_time,
                   const std::uint8_t* data, std::size_t size) {
  if (closed_) throw std::logic_error("mcap::Writer::write after close");
  if (!chunk_.b.empty() && (chunk_.b.size() + size > options_.chunk_bytes ||
                            log_time >= chunk_start_ + options_.chunk_span_ns || log_time < chunk_start_))
    flush_chunk();
  if (chunk_.b.empty()) chunk_start_ = chunk_end_ = log_time;
  chunk_index_[channel].emplace_back(log_time, chunk_.b.size());
  const auto at = chunk_.open(kMessage);
  chunk_.u16(channel);
  chunk_.u32(sequence);
  chunk_.u64(log_time);
  chunk_.u64(publish_time);
  chunk_.put(data, size);
  chunk_.close(at);
  chunk_end_ = std::max(chunk_end_, log_time);
  if (message_count_ == 0) first_time_ = last_time_ = log_time;
  first_time_ = std::min(first_time_, log_time);
  last_time_ = std::max(last_time_, log_time);
  ++message_count_;
  ++channel_counts_[channel];
}

void Writer::flush_chunk() {
  if (chunk_.b.empty()) return;
  // The records as they go into the file: compressed, or (no compression) as they are.
  const bool compress = compressor_.compression() != Compression::kNone;
  if (compress) compressor_.compress(chunk_.b.data(), chunk_.b.size(), compressed_);
  const std::vector<std::uint8_t>& stored = compress ? compressed_ : chunk_.b;
  ChunkIndex index{chunk_start_, chunk_end_, offset_, 0, 0, chunk_.b.size(), stored.size(), {}};
  Bytes r;
  r.b.reserve(stored.size() + 64 + chunk_index_.size() * 64);
  const auto at = r.open(kChunk);
  r.u64(chunk_start_);
  r.u64(chunk_end_);
  r.u64(chunk_.b.size());                           // uncompressed size
  r.u32(crc(0, chunk_.b.data(), chunk_.b.size()));  // uncompressed CRC
  r.str(compression_name(compressor_.compression()));
  r.u64(stored.size());
  r.put(stored.data(), stored.size());
  r.close(at);
  records_bytes_ += chunk_.b.size();
  index.length = r.b.size();
  // Its message indexes follow it: per channel, each message's log time and offset in the chunk.
  std::uint64_t index_at = offset_ + r.b.size();
  for (const auto& [channel, entries] : chunk_index_) {
    const auto mi = r.open(kMessageIndex);
    r.u16(channel);
    r.u32(static_cast<std::uint32_t>(entries.size() * 16));
    for (const auto& [time, offset] : entries) r.u64(time), r.u64(offset);
    r.close(mi);
    index.index_offsets[channel] = index_at;
    index_at = offset_ + r.b.size();
  }
  index.index_length = r.b.size() - index.length;
  emit(r);  // one write: a kill leaves either all of the chunk or a torn tail the reader stops at
  chunk_indexes_.push_back(std::move(index));
  chunk_.clear();
  chunk_index_.clear();
}

void Writer::close() {
  if (closed_ || fd_ < 0) return;
  flush_chunk();
  closed_ = true;
  Bytes end;
  const auto at = end.open(kDataEnd);
  end.u32(data_crc_);
  end.close(at);
  emit(end);
  // The summary: schemas, channels, statistics, chunk indexes; then where each group starts.
  const std::uint64_t summary_start = offset_;
  std::uint32_t summary_crc = 0;
  auto summary = [&](const Bytes& b) {
    emit(b, false);
    summary_crc = crc(summary_crc, b.b.data(), b.b.size());
  };
  struct Group {
    Op op;
    std::uint64_t start, length;
  };
  std::vector<Group> groups;
  auto group = [&](Op op, const Bytes& b) {
    if (b.b.empty()) return;
    groups.push_back(Group{op, offset_, b.b.size()});
    summary(b);
  };
  group(kSchema, schemas_);
  group(kChannel, channels_);
  Bytes stats;
  const auto st = stats.open(kStatistics);
  stats.u64(message_count_);
  stats.u16(static_cast<std::uint16_t>(next_schema_ - 1));
  stats.u32(static_cast<std::uint32_t>(next_channel_ - 1));
  stats.u32(0);  // attachments
  stats.u32(0);  // metadata
  stats.u32(static_cast<std::uint32_t>(chunk_indexes_.size()));
  stats.u64(first_time_);
  stats.u64(last_time_);
  stats.u32(static_cast<std::uint32_t>(channel_counts_.size() * 10));
  for (const auto& [channel, count] : channel_counts_) stats.u16(channel), stats.u64(count);
  stats.close(st);
  group(kStatistics, stats);
  Bytes chunks;
  for (const auto& c : chunk_indexes_) {
    const auto ci = chunks.open(kChunkIndex);
    chunks.u64(c.start_time);
    chunks.u64(c.end_time);
    chunks.u64(c.offset);
    chunks.u64(c.length);
    chunks.u32(static_cast<std::uint32_t>(c.index_offsets.size() * 10));
    for (const auto& [channel, offset] : c.index_offsets) chunks.u16(channel), chunks.u64(offset);
    chunks.u64(c.index_length);
    chunks.str(compression_name(compressor_.compression()));
    chunks.u64(c.compressed_size);
    chunks.u64(c.records_size);  // uncompressed size
    chunks.close(ci);
  }
  group(kChunkIndex, chunks);
  const std::uint64_t offsets_start = offset_;
  Bytes offsets;
  for (const auto& g : groups) {
    const auto so = offsets.open(kSummaryOffset);
    offsets.u8(g.op);
    offsets.u64(g.start);
    offsets.u64(g.length);
    offsets.close(so);
  }
  summary(offsets);
  // The footer; its CRC covers the summary through the footer's own offset fields.
  Bytes footer;
  footer.u8(kFooter);
  footer.u64(8 + 8 + 4);
  footer.u64(summary_start == offsets_start && groups.empty() ? 0 : summary_start);
  footer.u64(offsets.b.empty() ? 0 : offsets_start);
  summary_crc = crc(summary_crc, footer.b.data(), footer.b.size());
  footer.u32(summary_crc);
  footer.put(kMagic, sizeof kMagic);
  emit(footer, false);
  ::close(fd_);
  fd_ = -1;
}

}  // namespace wysiwyf::io::mcap
