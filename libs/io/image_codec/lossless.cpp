#include "image_codec/lossless.hpp"

#include <webp/decode.h>
#include <webp/encode.h>
#include <zstd.h>

#include <cstring>
#include <opencv2/imgcodecs.hpp>

namespace wysiwyf::io::image_codec {

namespace {

// Bytes per pixel of the 8-bit encodings WebP keeps; 0 for others.
int webp_channels(const std::string& encoding) {
  if (encoding == "mono8") return 1;
  if (encoding == "rgb8" || encoding == "bgr8") return 3;
  if (encoding == "rgba8" || encoding == "bgra8") return 4;
  return 0;
}

// What is wrong with a shape for a packing ("" when it fits): the layout the codec writes back.
std::string shape_problem(const Shape& s, Packing p) {
  const int bpp = p == Packing::kWebp ? webp_channels(s.encoding) : (s.encoding == "32FC1" && !s.is_bigendian) ? 4 : 0;
  if (bpp == 0) return "encoding '" + s.encoding + "' cannot be packed as " + packing_name(p);
  if (s.width == 0 || s.height == 0 || s.width > 16384 || s.height > 16384)
    return "size " + std::to_string(s.width) + "x" + std::to_string(s.height) + "; expected 1 to 16384 each";
  if (std::uint64_t{s.step} != std::uint64_t{s.width} * bpp)
    return "step " + std::to_string(s.step) + "; expected width x " + std::to_string(bpp) + " = " +
           std::to_string(std::uint64_t{s.width} * bpp);
  if (std::uint64_t{s.step} * s.height > kMaxImageBytes)
    return std::to_string(std::uint64_t{s.step} * s.height) + " bytes of pixels; at most " +
           std::to_string(kMaxImageBytes);
  return "";
}

std::string encode_webp(const ImageSample& im, CompressedFrame& out) {
  WebPConfig config;
  if (!WebPConfigInit(&config)) return "libwebp: version mismatch";
  config.lossless = 1;
  config.exact = 1;  // keep the colour under transparent pixels
  // Method 1: ~45 ms a 640x480 camera image on the 2-core dev VM, within 0.3 % of method 2's
  // size; method 0 is 3x faster but 21 % larger. (Quality, in lossless mode an effort, changed
  // nothing at method 1.)
  config.method = 1;
  config.quality = 0;
  WebPPicture pic;
  if (!WebPPictureInit(&pic)) return "libwebp: version mismatch";
  pic.use_argb = 1;
  pic.width = static_cast<int>(im.width);
  pic.height = static_cast<int>(im.height);
  const int stride = static_cast<int>(im.step);
  int ok = 0;
  if (im.encoding == "rgb8")
    ok = WebPPictureImportRGB(&pic, im.data.data(), stride);
  else if (im.encoding == "bgr8")
    ok = WebPPictureImportBGR(&pic, im.data.data(), stride);
  else if (im.encoding == "rgba8")
    ok = WebPPictureImportRGBA(&pic, im.data.data(), stride);
  else if (im.encoding == "bgra8")
    ok = WebPPictureImportBGRA(&pic, im.data.data(), stride);
  else if (im.encoding == "mono8" && (ok = WebPPictureAlloc(&pic))) {  // grey: R = G = B
    for (std::uint32_t y = 0; y < im.height; ++y)
      for (std::uint32_t x = 0; x < im.width; ++x) {
        const std::uint32_t g = im.data[y * im.step + x];
        pic.argb[y * pic.argb_stride + x] = 0xff000000u | g << 16 | g << 8 | g;
      }
  }
  if (!ok) {
    WebPPictureFree(&pic);
    return "libwebp could not take the pixels (out of memory)";
  }
  WebPMemoryWriter writer;
  WebPMemoryWriterInit(&writer);
  pic.writer = WebPMemoryWrite;
  pic.custom_ptr = &writer;
  const bool encoded = WebPEncode(&config, &pic);
  const int error = pic.error_code;
  WebPPictureFree(&pic);
  if (encoded) out.data.assign(writer.mem, writer.mem + writer.size);
  WebPMemoryWriterClear(&writer);
  if (!encoded) return "libwebp failed to encode (error " + std::to_string(error) + ")";
  out.format = "webp";
  return "";
}

std::string decode_webp(const std::uint8_t* d, std::size_t n, const Shape& s, std::vector<std::uint8_t>& pixels) {
  int w = 0, h = 0;
  if (!WebPGetInfo(d, n, &w, &h)) return "not a WebP image (" + std::to_string(n) + " bytes)";
  if (static_cast<std::uint32_t>(w) != s.width || static_cast<std::uint32_t>(h) != s.height)
    return "a WebP image of " + std::to_string(w) + "x" + std::to_string(h) + "; the recording says " +
           std::to_string(s.width) + "x" + std::to_string(s.height);
  pixels.resize(std::size_t{s.step} * s.height);
  const int stride = static_cast<int>(s.step);
  std::uint8_t* ok = nullptr;
  if (s.encoding == "rgb8")
    ok = WebPDecodeRGBInto(d, n, pixels.data(), pixels.size(), stride);
  else if (s.encoding == "bgr8")
    ok = WebPDecodeBGRInto(d, n, pixels.data(), pixels.size(), stride);
  else if (s.encoding == "rgba8")
    ok = WebPDecodeRGBAInto(d, n, pixels.data(), pixels.size(), stride);
  else if (s.encoding == "bgra8")
    ok = WebPDecodeBGRAInto(d, n, pixels.data(), pixels.size(), stride);
  else {  // mono8: the red of each grey pixel
    std::vector<std::uint8_t> rgb(std::size_t{s.width} * s.height * 3);
    if ((ok = WebPDecodeRGBInto(d, n, rgb.data(), rgb.size(), static_cast<int>(s.width * 3))))
      for (std::size_t i = 0; i < pixels.size(); ++i) pixels[i] = rgb[i * 3];
  }
  return ok ? "" : "a corrupt or truncated WebP image (" + std::to_string(n) + " bytes)";
}

std::uint32_t be32(const std::uint8_t* p) {
  return std::uint32_t{p[0]} << 24 | std::uint32_t{p[1]} << 16 | std::uint32_t{p[2]} << 8 | p[3];
}

std::string encode_float_planes(const ImageSample& im, CompressedFrame& out) {
  const std::size_t w = im.width, h = im.height;
  cv::Mat planes(static_cast<int>(4 * h), static_cast<int>(w), CV_8UC1);
  for (std::size_t y = 0; y < h; ++y) {
    std::uint32_t previous = 0;
    for (std::size_t x = 0; x < w; ++x) {
      std::uint32_t bits;
      std::memcpy(&bits, im.data.data() + y * im.step + 4 * x, 4);
      const std::uint32_t delta = bits - previous;  // modulo 2^32
      previous = bits;
      for (std::size_t b = 0; b < 4; ++b)
        planes.at<std::uint8_t>(static_cast<int>(b * h + y), static_cast<int>(x)) =
            static_cast<std::uint8_t>(delta >> (8 * (3 - b)));
    }
  }
  if (!cv::imencode(".png", planes, out.data, {cv::IMWRITE_PNG_COMPRESSION, 1})) return "OpenCV failed to write a PNG";
  out.format = "png";
  return "";
}

std::string decode_float_planes(const std::uint8_t* d, std::size_t n, const Shape& s,
                                std::vector<std::uint8_t>& pixels) {
  // The PNG's own header first (signature, IHDR: width, height, 8-bit grey), so that a file
  // cannot make the decoder allocate for a size other than the recording's.
  static const std::uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (n < 33 || std::memcmp(d, kSignature, 8) != 0 || std::memcmp(d + 12, "IHDR", 4) != 0)
    return "not a PNG image (" + std::to_string(n) + " bytes)";
  const std::uint32_t w = be32(d + 16), h = be32(d + 20);
  if (w != s.width || h != std::uint64_t{s.height} * 4 || d[24] != 8 || d[25] != 0)
    return "a PNG of " + std::to_string(w) + "x" + std::to_string(h) + ", " + std::to_string(d[24]) +
           "-bit, colour type " + std::to_string(d[25]) + "; the recording says " + std::to_string(s.width) + "x" +
           std::to_string(s.height) + " 32FC1, whose four byte planes make a " + std::to_string(s.width) + "x" +
           std::to_string(4 * s.height) + " 8-bit grey PNG";
  cv::Mat planes;
  try {
    planes = cv::imdecode(cv::Mat(1, static_cast<int>(n), CV_8UC1, const_cast<std::uint8_t*>(d)), cv::IMREAD_UNCHANGED);
  } catch (const cv::Exception& e) {
    return std::string("a corrupt PNG image: ") + e.what();
  }
  if (planes.empty() || planes.type() != CV_8UC1 || planes.cols != static_cast<int>(w) ||
      planes.rows != static_cast<int>(h))
    return "a corrupt or truncated PNG image (" + std::to_string(n) + " bytes)";
  pixels.resize(std::size_t{s.step} * s.height);
  for (std::size_t y = 0; y < s.height; ++y) {
    std::uint32_t bits = 0;
    for (std::size_t x = 0; x < s.width; ++x) {
      std::uint32_t delta = 0;
      for (std::size_t b = 0; b < 4; ++b)
        delta = delta << 8 | planes.at<std::uint8_t>(static_cast<int>(b * s.height + y), static_cast<int>(x));
      bits += delta;
      std::memcpy(pixels.data() + y * s.step + 4 * x, &bits, 4);
    }
  }
  return "";
}

}  // namespace

std::string packing_name(Packing p) {
  switch (p) {
    case Packing::kWebp: return "webp";
    case Packing::kFloatDeltaPng: return "float32-delta-planes-png";
    case Packing::kH264: return "h264";
    case Packing::kRaw: break;
  }
  return "raw";
}

bool parse_packing(const std::string& name, Packing& out) {
  for (Packing p : {Packing::kRaw, Packing::kWebp, Packing::kFloatDeltaPng, Packing::kH264})
    if (packing_name(p) == name) return out = p, true;
  return false;
}

Shape shape_of(const ImageSample& image) {
  return {image.height, image.width, image.step, image.encoding, image.is_bigendian};
}

Packing lossless_packing(const ImageSample& image) {
  const Shape s = shape_of(image);
  for (Packing p : {Packing::kWebp, Packing::kFloatDeltaPng})
    if (shape_problem(s, p).empty() && image.data.size() == std::size_t{s.step} * s.height) return p;
  return Packing::kRaw;
}

double zstd_share(const ImageSample& image) {
  if (image.data.empty()) return 1;
  std::vector<std::uint8_t> out(ZSTD_compressBound(image.data.size()));
  const std::size_t n = ZSTD_compress(out.data(), out.size(), image.data.data(), image.data.size(), 1);
  return ZSTD_isError(n) ? 1 : static_cast<double>(n) / static_cast<double>(image.data.size());
}

std::string encode_lossless(const ImageSample& image, Packing packing, CompressedFrame& out) {
  if (packing == Packing::kRaw || packing == Packing::kH264)
    return "packing '" + packing_name(packing) + "' is not a lossless image codec's";
  if (auto why = shape_problem(shape_of(image), packing); !why.empty()) return why;
  if (image.data.size() != std::size_t{image.step} * image.height)
    return std::to_string(image.data.size()) +
           " bytes of pixels; expected step x height = " + std::to_string(std::size_t{image.step} * image.height);
  if (packing == Packing::kWebp) return encode_webp(image, out);
  return encode_float_planes(image, out);
}

std::string decode_lossless(const std::uint8_t* data, std::size_t n, Packing packing, const Shape& shape,
                            std::vector<std::uint8_t>& pixels) {
  if (packing == Packing::kRaw || packing == Packing::kH264)
    return "packing '" + packing_name(packing) + "' is not a lossless image codec's";
  if (auto why = shape_problem(shape, packing); !why.empty()) return why;
  return packing == Packing::kWebp ? decode_webp(data, n, shape, pixels) : decode_float_planes(data, n, shape, pixels);
}

}  // namespace wysiwyf::io::image_codec
