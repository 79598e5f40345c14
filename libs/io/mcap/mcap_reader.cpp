#include "mcap/mcap_reader.hpp"

#include <zlib.h>

#include <cstring>
#include <stdexcept>

#include "mcap/mcap_records.hpp"

namespace wysiwyf::io::mcap {

Reader::Reader(const std::string& path) : path_(path), in_(path, std::ios::binary) {
  if (!in_) throw std::runtime_error("cannot read '" + path + "'");
  in_.seekg(0, std::ios::end);
  size_ = static_cast<std::uint64_t>(in_.tellg());
  rewind();
}

void Reader::rewind() {
  in_.clear();
  in_.seekg(0);
  std::uint8_t magic[8] = {};
  if (!in_.read(reinterpret_cast<char*>(magic), 8) || std::memcmp(magic, kMagic, 8) != 0)
    throw std::runtime_error("'" + path_ + "' is not an MCAP file (no MCAP magic at its start)");
  chunk_.clear();
  chunk_at_ = 0;
  problem_.clear();
  complete_ = ended_ = false;
}

bool Reader::read_record(std::uint8_t& op, std::vector<std::uint8_t>& content) {
  const std::uint64_t at = static_cast<std::uint64_t>(in_.tellg());
  record_at_ = at;
  std::uint64_t length = 0;
  if (!in_.read(reinterpret_cast<char*>(&op), 1) || !in_.read(reinterpret_cast<char*>(&length), 8)) {
    problem_ = "cut short at byte " + std::to_string(at) + " (no footer: the writer did not close it)";
    return false;
  }
  if (length > size_ - at - 9) {
    problem_ = "cut short at byte " + std::to_string(at) + ": a record of " + std::to_string(length) + " bytes with " +
               std::to_string(size_ - at - 9) + " left (the writer did not close it)";
    return false;
  }
  content.resize(length);
  in_.read(reinterpret_cast<char*>(content.data()), static_cast<std::streamsize>(length));
  return true;
}

bool Reader::handle(std::uint8_t op, const std::uint8_t* p, std::size_t n, Message& out) {
  Cursor c{p, n};
  if (op == kSchema) {
    Schema s;
    s.id = c.get<std::uint16_t>();
    s.name = c.str();
    s.encoding = c.str();
    s.data = c.str();
    if (c.ok) schemas_[s.id] = std::move(s);
  } else if (op == kChannel) {
    Channel ch;
    ch.id = c.get<std::uint16_t>();
    ch.schema_id = c.get<std::uint16_t>();
    ch.topic = c.str();
    ch.message_encoding = c.str();
    const auto map_end = c.get<std::uint32_t>() + c.at;
    while (c.ok && c.at < map_end) {
      std::string k = c.str();
      ch.metadata[k] = c.str();
    }
    if (c.ok) channels_[ch.id] = std::move(ch);
  } else if (op == kMessage) {
    out.channel = c.get<std::uint16_t>();
    out.sequence = c.get<std::uint32_t>();
    out.log_time = c.get<std::uint64_t>();
    out.publish_time = c.get<std::uint64_t>();
    if (!c.ok) return false;
    out.data.assign(p + c.at, p + n);
    return true;
  }
  return false;
}

bool Reader::next(Message& out) {
  while (!ended_) {
    // Inside a chunk: its records, one by one.
    while (chunk_at_ < chunk_.size()) {
      if (chunk_.size() - chunk_at_ < 9) break;
      const std::uint8_t op = chunk_[chunk_at_];
      std::uint64_t length = 0;
      std::memcpy(&length, chunk_.data() + chunk_at_ + 1, 8);
      if (length > chunk_.size() - chunk_at_ - 9) break;
      const std::uint8_t* content = chunk_.data() + chunk_at_ + 9;
      chunk_at_ += 9 + length;
      if (handle(op, content, length, out)) return true;
    }
    chunk_.clear();
    chunk_at_ = 0;
    std::uint8_t op = 0;
    if (!read_record(op, record_)) {
      ended_ = true;
      break;
    }
    if (op == kChunk) {
      Cursor c{record_.data(), record_.size()};
      c.get<std::uint64_t>();
      c.get<std::uint64_t>();
      const auto uncompressed = c.get<std::uint64_t>();
      const auto crc = c.get<std::uint32_t>();
      const std::string compression = c.str();
      const auto size = c.get<std::uint64_t>();
      const std::string where = "the chunk at byte " + std::to_string(record_at_) + ": ";
      if (!c.ok || size > record_.size() - c.at) {
        problem_ = where + "its record is malformed (its fields run past its end)";
        ended_ = true;
        break;
      }
      // Sizes are checked before anything is allocated for the chunk (Decompressor).
      const std::string why = decompressor_.decompress(compression, record_.data() + c.at, size, uncompressed, chunk_);
      if (!why.empty() || (crc != 0 && crc32_z(0, chunk_.data(), chunk_.size()) != crc)) {
        problem_ = where + (why.empty() ? "its records fail their CRC" : why);
        chunk_.clear();
        ended_ = true;
        break;
      }
    } else if (op == kDataEnd) {
      complete_ = true;  // (the summary repeats what the data section said)
      ended_ = true;
    } else if (handle(op, record_.data(), record_.size(), out)) {
      return true;
    }
  }
  return false;
}

}  // namespace wysiwyf::io::mcap
