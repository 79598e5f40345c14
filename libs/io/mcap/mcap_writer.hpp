#pragma once
// Writes an MCAP file: schemas and channels as they appear, messages in chunks (compressed with
// zstd by default, or lz4, or not; the CRC of the uncompressed records in each) each followed by
// its message indexes, and at close a summary (schemas, channels,
// statistics, chunk indexes) with summary offsets and the footer. Each chunk is written to the
// file when it closes (by size or by age), so a writer that is killed leaves a file that reads
// up to its last closed chunk; memory stays bounded by one chunk.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "mcap/mcap_compression.hpp"
#include "mcap/mcap_records.hpp"

namespace wysiwyf::io::mcap {

struct WriterOptions {
  std::string profile;                        // "" or e.g. "ros2"
  std::string library = "wysiwyf";            // who wrote the file
  std::size_t chunk_bytes = 4 * 1024 * 1024;  // a chunk closes when its records pass this size
  std::uint64_t chunk_span_ns = 500'000'000;  // ... or when its first message is this old (log time)
  Compression compression = Compression::kZstd;
  // zstd: 1 is its fastest positive level, and keeps up with the demo's images on the recorder's
  // one thread (docs/architecture.md, Recording); lz4: 0 is its fast mode.
  int compression_level = 1;
};

class Writer {
 public:
  // Creates (truncates) `path`; throws std::runtime_error saying why it cannot.
  Writer(const std::string& path, WriterOptions options = {});
  ~Writer();  // close()
  Writer(const Writer&) = delete;
  Writer& operator=(const Writer&) = delete;

  // Ids start at 1 (a schema id of 0 means "no schema").
  std::uint16_t add_schema(const std::string& name, const std::string& encoding, const std::string& data);
  std::uint16_t add_channel(std::uint16_t schema_id, const std::string& topic, const std::string& message_encoding,
                            const std::map<std::string, std::string>& metadata = {});
  void write(std::uint16_t channel, std::uint32_t sequence, std::uint64_t log_time, std::uint64_t publish_time,
             const std::uint8_t* data, std::size_t size);
  // Writes the open chunk to the file now (the recorder calls it when it stops).
  void flush_chunk();
  // Writes the last chunk, the summary and the footer; the file is complete. Idempotent.
  void close();

  std::uint64_t message_count() const { return message_count_; }
  std::uint64_t bytes_written() const { return offset_; }
  // The chunks' records before compression (what bytes_written() would near without it).
  std::uint64_t records_bytes() const { return records_bytes_; }
  std::uint32_t chunk_count() const { return static_cast<std::uint32_t>(chunk_indexes_.size()); }

 private:
  struct ChunkIndex {
    std::uint64_t start_time, end_time, offset, length, index_length, records_size, compressed_size;
    std::map<std::uint16_t, std::uint64_t> index_offsets;
  };
  void emit(const Bytes& bytes, bool data_section = true);

  int fd_ = -1;
  std::string path_;
  WriterOptions options_;
  std::uint64_t offset_ = 0;
  std::uint32_t data_crc_ = 0;
  Bytes schemas_, channels_;  // their records again, for the summary
  std::uint16_t next_schema_ = 1, next_channel_ = 1;
  // The open chunk: its records, its time span, each channel's (log time, offset) index.
  Bytes chunk_;
  Compressor compressor_;
  std::vector<std::uint8_t> compressed_;  // the chunk's records compressed (reused)
  std::uint64_t records_bytes_ = 0;
  std::uint64_t chunk_start_ = 0, chunk_end_ = 0;
  std::map<std::uint16_t, std::vector<std::pair<std::uint64_t, std::uint64_t>>> chunk_index_;
  std::vector<ChunkIndex> chunk_indexes_;
  std::uint64_t message_count_ = 0, first_time_ = 0, last_time_ = 0;
  std::map<std::uint16_t, std::uint64_t> channel_counts_;
  bool closed_ = false;
};

}  // namespace wysiwyf::io::mcap
