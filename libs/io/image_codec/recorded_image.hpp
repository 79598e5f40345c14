#pragma once
// An Image sample as a recording keeps it on a packed channel: a foxglove CompressedImage (or,
// for kH264, a CompressedVideo access unit) whose channel metadata holds what that message lacks
// (the encoding, size and row step, the packing, a depth video's range), and whose MCAP message
// sequence is the image header's seq. Together they give the original sample back: byte for
// byte from the lossless packings, the same header, size and encoding from a video.
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "image_codec/lossless.hpp"
#include "image_codec/video.hpp"

namespace wysiwyf::io::image_codec {

using Metadata = std::map<std::string, std::string>;

// The metadata keys of a packed channel: image_packing (packing_name()), image_encoding,
// image_width, image_height, image_step, image_is_bigendian; for a depth video image_depth_max
// (metres at grey level 255).
Metadata packed_metadata(const Shape& shape, Packing packing, float depth_max = 0);
// Whether a channel with this metadata holds packed images (it has image_packing).
bool is_packed(const Metadata& metadata);

// Why `image` cannot go on a packed channel of `packing` and `shape` ("" if it can): another shape,
// a stamp outside foxglove.Time (0 to 2^32 s), a seq over 2^32 - 1 (the MCAP sequence's size).
std::string unpackable(const ImageSample& image, const Shape& shape, Packing packing);
// The CompressedImage CDR of `image` (checked by unpackable() first). "" on success, else why not.
std::string pack(const ImageSample& image, Packing packing, std::vector<std::uint8_t>& cdr);
// The CompressedVideo CDR of `image`, the next of its topic's stream.
std::string pack_video(const ImageSample& image, VideoEncoder& encoder, std::vector<std::uint8_t>& cdr);
// The depth at grey level 255 of a depth video whose first image is `image`: a quarter above
// its farthest depth (at least 1 cm).
float depth_max_for(const ImageSample& image);

// The Image CDR of a packed message, from its channel's metadata, its MCAP sequence and its
// bytes. "" on success, else what was wrong (metadata missing or out of range, the
// CompressedImage's CDR, the compressed image itself). `video`: the channel's decoder, made by
// the first call on an h264 channel and kept by the caller for the next (one per channel).
std::string unpack(const Metadata& metadata, std::uint32_t sequence, const std::uint8_t* p, std::size_t n,
                   std::vector<std::uint8_t>& out, std::unique_ptr<VideoDecoder>& video);

}  // namespace wysiwyf::io::image_codec
