#include "mcap/mcap_compression.hpp"

#include <lz4frame.h>
#include <zstd.h>

#include <stdexcept>

namespace wysiwyf::io::mcap {

std::string compression_name(Compression c) {
  switch (c) {
    case Compression::kZstd: return "zstd";
    case Compression::kLz4: return "lz4";
    case Compression::kNone: break;
  }
  return "";
}

std::optional<Compression> parse_compression(const std::string& name) {
  if (name == "zstd") return Compression::kZstd;
  if (name == "lz4") return Compression::kLz4;
  if (name == "none") return Compression::kNone;
  return std::nullopt;
}

struct Compressor::Contexts {
  ZSTD_CCtx* zstd = nullptr;
  LZ4F_cctx* lz4 = nullptr;
  ~Contexts() {
    ZSTD_freeCCtx(zstd);
    LZ4F_freeCompressionContext(lz4);
  }
};

Compressor::Compressor(Compression c, int level) : compression_(c), level_(level), ctx_(new Contexts) {
  if (c == Compression::kZstd && !(ctx_->zstd = ZSTD_createCCtx()))
    throw std::runtime_error("zstd: cannot create a compression context");
  if (c == Compression::kLz4 && LZ4F_isError(LZ4F_createCompressionContext(&ctx_->lz4, LZ4F_VERSION)))
    throw std::runtime_error("lz4: cannot create a compression context");
}

Compressor::~Compressor() = default;

void Compressor::compress(const std::uint8_t* p, std::size_t n, std::vector<std::uint8_t>& out) {
  if (compression_ == Compression::kNone) {
    out.assign(p, p + n);
    return;
  }
  if (compression_ == Compression::kZstd) {
    // (ZSTD_compressCCtx writes the content size into the frame header: readers check it.)
    out.resize(ZSTD_compressBound(n));
    const std::size_t r = ZSTD_compressCCtx(ctx_->zstd, out.data(), out.size(), p, n, level_);
    if (ZSTD_isError(r)) throw std::runtime_error(std::string("zstd: ") + ZSTD_getErrorName(r));
    out.resize(r);
    return;
  }
  LZ4F_preferences_t prefs = LZ4F_INIT_PREFERENCES;
  prefs.frameInfo.contentSize = n;  // in the header: readers check it against the chunk's size
  prefs.compressionLevel = level_;
  out.resize(LZ4F_HEADER_SIZE_MAX + LZ4F_compressBound(n, &prefs));
  std::size_t at = LZ4F_compressBegin(ctx_->lz4, out.data(), out.size(), &prefs);
  std::size_t r = at;
  if (!LZ4F_isError(r)) r = LZ4F_compressUpdate(ctx_->lz4, out.data() + at, out.size() - at, p, n, nullptr);
  if (!LZ4F_isError(r)) at += r, r = LZ4F_compressEnd(ctx_->lz4, out.data() + at, out.size() - at, nullptr);
  if (LZ4F_isError(r)) throw std::runtime_error(std::string("lz4: ") + LZ4F_getErrorName(r));
  out.resize(at + r);
}

struct Decompressor::Contexts {
  ZSTD_DCtx* zstd = nullptr;
  LZ4F_dctx* lz4 = nullptr;
  ~Contexts() {
    ZSTD_freeDCtx(zstd);
    LZ4F_freeDecompressionContext(lz4);
  }
};

Decompressor::Decompressor() : ctx_(new Contexts) {}
Decompressor::~Decompressor() = default;

std::string Decompressor::decompress(const std::string& compression, const std::uint8_t* p, std::size_t n,
                                     std::uint64_t uncompressed_size, std::vector<std::uint8_t>& out) {
  if (compression != "" && compression != "zstd" && compression != "lz4")
    return "compression '" + compression + "' is not supported (zstd, lz4 or none)";
  if (uncompressed_size > kMaxChunkBytes)
    return "it claims " + std::to_string(uncompressed_size) + " bytes uncompressed, over the " +
           std::to_string(kMaxChunkBytes) + " bytes a reader accepts for one chunk";
  if (compression.empty()) {
    if (n != uncompressed_size)
      return "uncompressed, it has " + std::to_string(n) + " bytes and claims " + std::to_string(uncompressed_size);
    out.assign(p, p + n);
    return "";
  }
  return compression == "zstd" ? zstd(p, n, uncompressed_size, out) : lz4(p, n, uncompressed_size, out);
}

std::string Decompressor::zstd(const std::uint8_t* p, std::size_t n, std::uint64_t size,
                               std::vector<std::uint8_t>& out) {
  // The frame header's own size first (nothing allocated yet): a frame that is not zstd, or
  // that says it holds more than the chunk claims, is refused here.
  const unsigned long long framed = ZSTD_getFrameContentSize(p, n);
  if (framed == ZSTD_CONTENTSIZE_ERROR) return "zstd: no valid frame header at its start";
  if (framed != ZSTD_CONTENTSIZE_UNKNOWN && framed > size)
    return "zstd: its frame holds " + std::to_string(framed) + " bytes; the chunk claims " + std::to_string(size);
  if (!ctx_->zstd && !(ctx_->zstd = ZSTD_createDCtx())) return "zstd: cannot create a decompression context";
  out.resize(size);
  const std::size_t r = ZSTD_decompressDCtx(ctx_->zstd, out.data(), out.size(), p, n);
  if (ZSTD_isError(r)) {
    out.clear();
    return std::string("zstd: it does not decompress (") + ZSTD_getErrorName(r) + ")";
  }
  if (r != size) {
    out.clear();
    return "zstd: it decompresses to " + std::to_string(r) + " bytes; the chunk claims " + std::to_string(size);
  }
  return "";
}

std::string Decompressor::lz4(const std::uint8_t* p, std::size_t n, std::uint64_t size,
                              std::vector<std::uint8_t>& out) {
  if (!ctx_->lz4 && LZ4F_isError(LZ4F_createDecompressionContext(&ctx_->lz4, LZ4F_VERSION)))
    return "lz4: cannot create a decompression context";
  LZ4F_resetDecompressionContext(ctx_->lz4);  // (a previous corrupt chunk may have left it mid-frame)
  LZ4F_frameInfo_t info{};
  std::size_t in = n;
  std::size_t r = LZ4F_getFrameInfo(ctx_->lz4, &info, p, &in);  // reads the header; `in` = its size
  if (LZ4F_isError(r)) return std::string("lz4: no valid frame header at its start (") + LZ4F_getErrorName(r) + ")";
  if (info.contentSize != 0 && info.contentSize != size)
    return "lz4: its frame holds " + std::to_string(info.contentSize) + " bytes; the chunk claims " +
           std::to_string(size);
  out.resize(size);
  std::size_t out_at = 0;
  while (r != 0) {  // 0: the frame is complete
    if (in == n) {
      out.clear();
      return "lz4: it ends before its frame does (truncated)";
    }
    std::size_t src = n - in, dst = out.size() - out_at;
    r = LZ4F_decompress(ctx_->lz4, out.data() + out_at, &dst, p + in, &src, nullptr);
    if (LZ4F_isError(r)) {
      out.clear();
      return std::string("lz4: it does not decompress (") + LZ4F_getErrorName(r) + ")";
    }
    in += src, out_at += dst;
    if (r != 0 && src == 0 && dst == 0) {  // no progress: the output is full, the frame goes on
      out.clear();
      return "lz4: it decompresses to more than the " + std::to_string(size) + " bytes the chunk claims";
    }
  }
  if (out_at != size || in != n) {
    out.clear();
    return "lz4: it decompresses to " + std::to_string(out_at) + " bytes in " + std::to_string(in) + " of its " +
           std::to_string(n) + "; the chunk claims " + std::to_string(size) + " in all of them";
  }
  return "";
}

}  // namespace wysiwyf::io::mcap
