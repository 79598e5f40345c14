#pragma once
// Lossless image compression for recordings: the pixels of an Image in a format Foxglove's
// CompressedImage carries, decoded back bit for bit.
//  - 8-bit images (mono8, rgb8, bgr8, rgba8, bgra8): lossless WebP (libwebp, exact: the colour
//    under a transparent pixel is kept). On the simulated cameras' noisy images it keeps 42 % of
//    the pixels' bytes, where PNG keeps 53 % and zstd 65 % (docs/performance.md, Recording).
//  - float depth (32FC1, little endian): a PNG of four 8-bit planes, most significant byte first,
//    of each row's differences between neighbouring pixels' bit patterns (smooth depth gives
//    small differences, so the upper planes are nearly constant). Browsers show it as a grey
//    picture four times as tall; `wysiwyf play` turns it back into the depth image.
// Decoding checks the compressed image's own header (format, size, layout) against the shape the
// recording claims before allocating, and refuses what does not match with a reason.
#include <cstdint>
#include <string>
#include <vector>

#include "image_codec/image_cdr.hpp"

namespace wysiwyf::io::image_codec {

// How an image's pixels are kept. Names as recorded in a channel's metadata. kH264 is lossy
// (video.hpp); the others give the pixels back bit for bit.
enum class Packing { kRaw, kWebp, kFloatDeltaPng, kH264 };
std::string packing_name(Packing p);  // "raw", "webp", "float32-delta-planes-png", "h264"
bool parse_packing(const std::string& name, Packing& out);

// What a decoder needs besides the compressed bytes (the Image fields a CompressedImage lacks).
struct Shape {
  std::uint32_t height = 0, width = 0, step = 0;
  std::string encoding;
  std::uint8_t is_bigendian = 0;
};
Shape shape_of(const ImageSample& image);

// The packing for an image of this encoding and layout: kRaw where none applies (another
// encoding, rows with padding, data not step x height).
Packing lossless_packing(const ImageSample& image);
// The share of its pixel bytes that zstd at level 1 (the recorder's chunk compression) leaves of
// this image: rendered and synthetic images come out under 0.05, where an image codec saves
// little more at ten times the cost.
double zstd_share(const ImageSample& image);

// The compressed pixels of `image` in `packing` into out.data and out.format. "" on success, else
// why not (a packing that does not fit the image, a codec failure).
std::string encode_lossless(const ImageSample& image, Packing packing, CompressedFrame& out);
// The pixels (step x height bytes) that `data` in `packing` holds for an image of `shape`. ""
// on success, else what was wrong: a format that is not the packing's, a size or layout other
// than the shape's, corrupt or truncated data.
std::string decode_lossless(const std::uint8_t* data, std::size_t n, Packing packing, const Shape& shape,
                            std::vector<std::uint8_t>& pixels);

}  // namespace wysiwyf::io::image_codec
