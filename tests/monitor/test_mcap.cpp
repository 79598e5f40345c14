// libs/io/mcap: files written with each chunk compression (zstd, lz4, none) read back message for
// message, and hostile files (a chunk claiming 100 GB, a truncated or corrupt compressed chunk,
// an unknown compression) refused with a clear problem(), without a crash and without
// allocating what the file claims.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <ostream>
#include <random>
#include <string>
#include <vector>

#include "mcap/mcap_compression.hpp"
#include "mcap/mcap_reader.hpp"
#include "mcap/mcap_records.hpp"
#include "mcap/mcap_writer.hpp"

namespace wysiwyf::io::mcap {
namespace {

namespace fs = std::filesystem;

std::string label(Compression c) { return c == Compression::kNone ? "none" : compression_name(c); }
}  // namespace
void PrintTo(Compression c, std::ostream* os) { *os << label(c); }  // (gtest's names of the cases)
namespace {

// A file of this test's own (ctest runs the cases in parallel, each in its own process).
fs::path scratch(const std::string& name) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string test = std::string(info->test_suite_name()) + "." + info->name();
  for (char& c : test)
    if (c == '/') c = '_';
  const fs::path dir = fs::path(WYSIWYF_TEST_SCRATCH_DIR) / "mcap" / test;
  fs::create_directories(dir);
  return dir / name;
}

// A message's payload: half text that compresses, half random bytes that do not.
std::vector<std::uint8_t> payload(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<std::uint8_t> p(n);
  for (std::size_t i = 0; i < n; ++i) p[i] = i % 2 ? static_cast<std::uint8_t>(rng()) : "wysiwyf "[i / 2 % 8];
  return p;
}

// Writes 300 messages on two channels (one of them 1 MB, larger than a chunk) in 64 kB chunks.
std::vector<std::vector<std::uint8_t>> write_file(const fs::path& path, Compression c) {
  WriterOptions options;
  options.chunk_bytes = 64 * 1024;
  options.compression = c;
  Writer w(path.string(), options);
  const auto schema = w.add_schema("test::Blob", "omgidl", "module test { struct Blob { sequence<octet> b; }; };");
  const std::uint16_t channels[] = {w.add_channel(schema, "small", "cdr"), w.add_channel(schema, "large", "cdr")};
  std::vector<std::vector<std::uint8_t>> sent;
  for (unsigned i = 0; i < 300; ++i) {
    sent.push_back(payload(i == 150 ? 1 << 20 : 100 + i * 7, i));
    w.write(channels[i == 150], i, 1000 * i, 1000 * i, sent.back().data(), sent.back().size());
  }
  w.close();
  return sent;
}

// The file as records (opcode, content) after the magic, and back.
struct Record {
  std::uint8_t op;
  std::vector<std::uint8_t> content;
};
std::vector<Record> records(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::vector<std::uint8_t> b((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::vector<Record> out;
  std::size_t at = 8;
  while (b.size() - at >= 9) {
    std::uint64_t n = 0;
    std::memcpy(&n, b.data() + at + 1, 8);
    out.push_back({b[at], std::vector<std::uint8_t>(b.begin() + at + 9, b.begin() + at + 9 + n)});
    at += 9 + n;
    if (out.back().op == kFooter) break;
  }
  return out;
}
void write_records(const fs::path& path, const std::vector<Record>& rs) {
  Bytes b;
  b.put(kMagic, sizeof kMagic);
  for (const auto& r : rs) {
    b.u8(r.op);
    b.u64(r.content.size());
    b.put(r.content.data(), r.content.size());
  }
  b.put(kMagic, sizeof kMagic);
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(b.b.data()), b.b.size());
}

// A Chunk record's fields, and its content rebuilt from them.
struct Chunk {
  std::uint64_t start, end, uncompressed_size;
  std::uint32_t crc;
  std::string compression;
  std::vector<std::uint8_t> data;
};
Chunk parse_chunk(const std::vector<std::uint8_t>& content) {
  Cursor c{content.data(), content.size()};
  Chunk k;
  k.start = c.get<std::uint64_t>();
  k.end = c.get<std::uint64_t>();
  k.uncompressed_size = c.get<std::uint64_t>();
  k.crc = c.get<std::uint32_t>();
  k.compression = c.str();
  const auto n = c.get<std::uint64_t>();
  k.data.assign(content.begin() + static_cast<std::ptrdiff_t>(c.at),
                content.begin() + static_cast<std::ptrdiff_t>(c.at + n));
  return k;
}
std::vector<std::uint8_t> chunk_content(const Chunk& k) {
  Bytes b;
  b.u64(k.start), b.u64(k.end), b.u64(k.uncompressed_size), b.u32(k.crc), b.str(k.compression);
  b.u64(k.data.size());
  b.put(k.data.data(), k.data.size());
  return b.b;
}

class McapCompression : public ::testing::TestWithParam<Compression> {};

TEST_P(McapCompression, RoundTripsEveryMessage) {
  const Compression c = GetParam();
  const fs::path path = scratch("round-" + label(c) + ".mcap");
  const auto sent = write_file(path, c);
  Reader reader(path.string());
  Message m;
  std::size_t i = 0;
  while (reader.next(m)) {
    ASSERT_LT(i, sent.size());
    EXPECT_EQ(m.sequence, i);
    EXPECT_EQ(m.log_time, 1000u * i);
    EXPECT_EQ(m.channel, i == 150 ? 2 : 1);
    ASSERT_EQ(m.data, sent[i]) << "message " << i;
    ++i;
  }
  EXPECT_EQ(i, sent.size());
  EXPECT_EQ(reader.problem(), "");
  EXPECT_TRUE(reader.complete());
  EXPECT_EQ(reader.schemas().at(1).name, "test::Blob");
  // Every chunk, and every chunk index of the summary, names the compression.
  int chunks = 0, indexes = 0;
  for (const auto& r : records(path)) {
    if (r.op == kChunk) {
      ++chunks;
      EXPECT_EQ(parse_chunk(r.content).compression, compression_name(c));
    } else if (r.op == kChunkIndex) {
      ++indexes;
      Cursor cur{r.content.data(), r.content.size()};
      cur.take(32);
      cur.take(cur.get<std::uint32_t>() + 8);
      EXPECT_EQ(cur.str(), compression_name(c));
    }
  }
  EXPECT_GT(chunks, 3);
  EXPECT_EQ(chunks, indexes);
}

TEST_P(McapCompression, CompressesWhatCompresses) {
  const Compression c = GetParam();
  const fs::path path = scratch("size-" + label(c) + ".mcap");
  WriterOptions options;
  options.compression = c;
  Writer w(path.string(), options);
  const auto channel = w.add_channel(0, "zeros", "cdr");
  const std::vector<std::uint8_t> zeros(100000, 0);
  for (unsigned i = 0; i < 50; ++i) w.write(channel, i, i, i, zeros.data(), zeros.size());
  w.close();
  EXPECT_GT(w.records_bytes(), 5'000'000u);
  if (c == Compression::kNone)
    EXPECT_GT(w.bytes_written(), w.records_bytes());
  else
    EXPECT_LT(w.bytes_written(), w.records_bytes() / 50);
}

INSTANTIATE_TEST_SUITE_P(All, McapCompression,
                         ::testing::Values(Compression::kZstd, Compression::kLz4, Compression::kNone),
                         [](const auto& info) { return label(info.param); });

// Rewrites the first chunk of a file written with `c` by `change`, and reads the result to
// where reading stops.
struct Outcome {
  std::string problem;
  std::size_t messages = 0;
  bool complete = false;
};
Outcome read_with_first_chunk_changed(Compression c, const std::function<void(Chunk&)>& change) {
  const fs::path path = scratch("hostile-" + label(c) + ".mcap");
  write_file(path, c);
  auto rs = records(path);
  for (auto& r : rs)
    if (r.op == kChunk) {
      Chunk k = parse_chunk(r.content);
      change(k);
      r.content = chunk_content(k);
      break;
    }
  write_records(path, rs);
  Reader reader(path.string());
  Outcome o;
  Message m;
  while (reader.next(m)) ++o.messages;
  o.problem = reader.problem();
  o.complete = reader.complete();
  return o;
}

TEST(McapHostile, ChunkClaiming100GBIsRefusedBeforeAllocating) {
  for (Compression c : {Compression::kZstd, Compression::kLz4, Compression::kNone}) {
    const Outcome o = read_with_first_chunk_changed(c, [](Chunk& k) { k.uncompressed_size = 100'000'000'000ull; });
    EXPECT_NE(o.problem.find("the chunk at byte "), std::string::npos) << o.problem;
    EXPECT_NE(o.problem.find("claims 100000000000 bytes uncompressed"), std::string::npos) << o.problem;
    EXPECT_EQ(o.messages, 0u);
    EXPECT_FALSE(o.complete);
  }
  // The decompressor alone: nothing allocated for the claim.
  Decompressor d;
  std::vector<std::uint8_t> out;
  const std::uint8_t frame[] = {0x28, 0xB5, 0x2F, 0xFD, 0, 0, 0, 0};
  EXPECT_NE(d.decompress("zstd", frame, sizeof frame, 100'000'000'000ull, out), "");
  EXPECT_EQ(out.capacity(), 0u);
}

TEST(McapHostile, TruncatedCompressedChunkIsRefused) {
  for (Compression c : {Compression::kZstd, Compression::kLz4}) {
    const Outcome o = read_with_first_chunk_changed(c, [](Chunk& k) { k.data.resize(k.data.size() / 2); });
    EXPECT_NE(o.problem.find("the chunk at byte "), std::string::npos) << o.problem;
    EXPECT_TRUE(o.problem.find("does not decompress") != std::string::npos ||
                o.problem.find("truncated") != std::string::npos)
        << o.problem;
    EXPECT_EQ(o.messages, 0u);
  }
}

TEST(McapHostile, GarbageInAZstdFrameIsRefused) {
  // After the frame header: the blocks are garbage.
  Outcome o = read_with_first_chunk_changed(Compression::kZstd, [](Chunk& k) {
    std::mt19937 rng(7);
    for (std::size_t i = 20; i < k.data.size(); ++i) k.data[i] = static_cast<std::uint8_t>(rng());
  });
  EXPECT_NE(o.problem.find("does not decompress"), std::string::npos) << o.problem;
  // No frame at all.
  o = read_with_first_chunk_changed(Compression::kZstd, [](Chunk& k) { std::memset(k.data.data(), 0xAB, 16); });
  EXPECT_NE(o.problem.find("zstd: no valid frame header"), std::string::npos) << o.problem;
  // A frame that holds more than the chunk claims.
  o = read_with_first_chunk_changed(Compression::kZstd, [](Chunk& k) { --k.uncompressed_size; });
  EXPECT_NE(o.problem.find("the chunk claims"), std::string::npos) << o.problem;
  // An lz4 frame whose header says another size.
  o = read_with_first_chunk_changed(Compression::kLz4, [](Chunk& k) { ++k.uncompressed_size; });
  EXPECT_NE(o.problem.find("the chunk claims"), std::string::npos) << o.problem;
}

TEST(McapHostile, UnknownCompressionIsNamed) {
  const Outcome o = read_with_first_chunk_changed(Compression::kZstd, [](Chunk& k) { k.compression = "bz2"; });
  EXPECT_NE(o.problem.find("'bz2' is not supported"), std::string::npos) << o.problem;
}

TEST(McapHostile, FlippedBytesNeverCrashAndNeverPassUnnoticed) {
  // Any byte of a compressed chunk changed: the chunk is refused, or (a byte the codec ignores)
  // its records pass the CRC and the whole file reads.
  for (Compression c : {Compression::kZstd, Compression::kLz4}) {
    std::mt19937 rng(11);
    int refused = 0;
    for (int trial = 0; trial < 100; ++trial) {
      const Outcome o = read_with_first_chunk_changed(
          c, [&](Chunk& k) { k.data[rng() % k.data.size()] ^= static_cast<std::uint8_t>(1 + rng() % 255); });
      if (o.problem.empty()) {
        EXPECT_EQ(o.messages, 300u);
        EXPECT_TRUE(o.complete);
      } else {
        ++refused;
        EXPECT_NE(o.problem.find("the chunk at byte "), std::string::npos) << o.problem;
        EXPECT_EQ(o.messages, 0u);
      }
    }
    EXPECT_GT(refused, 50) << label(c);
  }
}

}  // namespace
}  // namespace wysiwyf::io::mcap
