#pragma once
// Chunk compression as the MCAP specification names it: "zstd" (a Zstandard frame), "lz4" (an
// LZ4 frame) or "" (none). The codecs are Debian's libzstd and liblz4; this file only drives them
// and checks every size a file claims before allocating for it.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace wysiwyf::io::mcap {

enum class Compression { kZstd, kLz4, kNone };

// The name a Chunk record carries: "zstd", "lz4" or "".
std::string compression_name(Compression c);
// From a command line: "zstd", "lz4" or "none"; nullopt for anything else.
std::optional<Compression> parse_compression(const std::string& name);

// The most a chunk may hold uncompressed before a reader refuses it: a file cannot make the
// reader allocate more than this for one chunk. Writers close chunks at a few MB; one message
// larger than that gets a chunk of its own, so this leaves room for 256 MB messages.
inline constexpr std::uint64_t kMaxChunkBytes = std::uint64_t{256} << 20;

// Compresses chunks; keeps its codec's context between chunks (no allocation per chunk once warm).
class Compressor {
 public:
  // `level`: zstd's level (1 fastest; 0 = zstd's default, 3) or lz4's (0 = the fast mode).
  explicit Compressor(Compression c, int level = 0);
  ~Compressor();
  Compressor(const Compressor&) = delete;
  Compressor& operator=(const Compressor&) = delete;

  Compression compression() const { return compression_; }
  // `out` = the compressed frame of p[0, n) (for kNone: a copy). Throws std::runtime_error if the
  // codec fails (it does not on valid input: the buffer is sized by the codec's own bound).
  void compress(const std::uint8_t* p, std::size_t n, std::vector<std::uint8_t>& out);

 private:
  struct Contexts;
  Compression compression_;
  int level_;
  std::unique_ptr<Contexts> ctx_;
};

// Decompresses chunks of any of the three kinds, refusing what does not add up.
class Decompressor {
 public:
  Decompressor();
  ~Decompressor();
  Decompressor(const Decompressor&) = delete;
  Decompressor& operator=(const Decompressor&) = delete;

  // `out` = the `uncompressed_size` bytes that p[0, n) decompresses to with `compression` (the
  // Chunk record's field). Returns "" on success, else why not: an unknown compression, a size
  // over kMaxChunkBytes, a frame whose header says another size, a corrupt or truncated frame,
  // data that decompresses to more or fewer bytes than claimed. Checks sizes before allocating.
  std::string decompress(const std::string& compression, const std::uint8_t* p, std::size_t n,
                         std::uint64_t uncompressed_size, std::vector<std::uint8_t>& out);

 private:
  std::string zstd(const std::uint8_t* p, std::size_t n, std::uint64_t size, std::vector<std::uint8_t>& out);
  std::string lz4(const std::uint8_t* p, std::size_t n, std::uint64_t size, std::vector<std::uint8_t>& out);
  struct Contexts;
  std::unique_ptr<Contexts> ctx_;
};

}  // namespace wysiwyf::io::mcap
