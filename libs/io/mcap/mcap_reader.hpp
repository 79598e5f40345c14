#pragma once
// Reads an MCAP file front to back (schemas, channels and messages, inside chunks or not), as
// far as it is whole: a file whose writer was killed reads up to its last complete record and
// says it was cut short. Chunks may be compressed with zstd or lz4, or not; a chunk that is
// corrupt, truncated or claims more than kMaxChunkBytes ends the reading with problem() saying
// so (nothing is allocated for a size the file claims before it is checked). Used by
// `wysiwyf play` and by the tests.
#include <cstdint>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "mcap/mcap_compression.hpp"

namespace wysiwyf::io::mcap {

struct Schema {
  std::uint16_t id = 0;
  std::string name, encoding, data;
};

struct Channel {
  std::uint16_t id = 0, schema_id = 0;
  std::string topic, message_encoding;
  std::map<std::string, std::string> metadata;
};

struct Message {
  std::uint16_t channel = 0;
  std::uint32_t sequence = 0;
  std::uint64_t log_time = 0, publish_time = 0;
  std::vector<std::uint8_t> data;
};

class Reader {
 public:
  // Throws std::runtime_error when `path` cannot be read or is not an MCAP file.
  explicit Reader(const std::string& path);

  // The next message in file order; false at the end (or where the file is cut short).
  bool next(Message& out);
  // Back to the first message (for looping).
  void rewind();

  const std::map<std::uint16_t, Schema>& schemas() const { return schemas_; }
  const std::map<std::uint16_t, Channel>& channels() const { return channels_; }
  // Why reading stopped before the footer ("" while reading, or after a complete file).
  const std::string& problem() const { return problem_; }
  bool complete() const { return complete_; }

 private:
  bool read_record(std::uint8_t& op, std::vector<std::uint8_t>& content);
  // Handles one record's content; a message goes to `out` (true).
  bool handle(std::uint8_t op, const std::uint8_t* p, std::size_t n, Message& out);

  std::string path_;
  std::ifstream in_;
  std::uint64_t size_ = 0;
  std::map<std::uint16_t, Schema> schemas_;
  std::map<std::uint16_t, Channel> channels_;
  std::vector<std::uint8_t> record_, chunk_;  // the current record; the chunk being read
  std::uint64_t record_at_ = 0;               // where the current record starts in the file
  Decompressor decompressor_;
  std::size_t chunk_at_ = 0;
  std::string problem_;
  bool complete_ = false, ended_ = false;
};

}  // namespace wysiwyf::io::mcap
