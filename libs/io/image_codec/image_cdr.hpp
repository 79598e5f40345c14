#pragma once
// The two message layouts an image recording converts between, as CDR bytes (XCDR1, little
// endian, with the 4-byte encapsulation header): this project's wysiwyf::msg::Image
// (interfaces/msgs/sensor_msgs.idl) and Foxglove's CompressedImage / CompressedVideo (a time,
// a frame id, the compressed bytes and their format). Parsing checks every length against the
// bytes there are, so a corrupt sample is refused with a reason instead of read past its end.
#include <cstdint>
#include <string>
#include <vector>

namespace wysiwyf::io::image_codec {

// The most pixel bytes an Image may carry (its IDL bound: 1280 x 720 x 4).
inline constexpr std::uint32_t kMaxImageBytes = 3686400;

// A wysiwyf::msg::Image with its header.
struct ImageSample {
  std::int64_t stamp_ns = 0;
  std::uint64_t seq = 0;
  std::string frame_id;
  std::uint32_t height = 0, width = 0;
  std::string encoding;
  std::uint8_t is_bigendian = 0;
  std::uint32_t step = 0;
  std::vector<std::uint8_t> data;
};

// Reads an Image sample. "" on success, else what was wrong (a short buffer, a length past the
// end, trailing bytes, padding that is not zero: anything that image_cdr() would not write back
// byte for byte).
std::string parse_image(const std::uint8_t* p, std::size_t n, ImageSample& out);
// The CDR bytes of `image`, as Fast DDS writes them (zero padding).
std::vector<std::uint8_t> image_cdr(const ImageSample& image);

// A foxglove CompressedImage or CompressedVideo: the same fields.
struct CompressedFrame {
  std::int64_t stamp_ns = 0;  // as foxglove.Time: seconds and nanoseconds, 0 <= stamp < 2^32 s
  std::string frame_id;
  std::vector<std::uint8_t> data;
  std::string format;  // "webp", "png", "h264"
};

std::string parse_compressed(const std::uint8_t* p, std::size_t n, CompressedFrame& out);
std::vector<std::uint8_t> compressed_cdr(const CompressedFrame& frame);

// Foxglove's schemas in OMG IDL (foxglove-sdk's omgidl folder, Time inlined so that the schema
// stands alone), under the names Foxglove's panels recognise.
inline constexpr const char* kCompressedImageName = "foxglove::CompressedImage";
inline constexpr const char* kCompressedVideoName = "foxglove::CompressedVideo";
std::string compressed_image_idl();
std::string compressed_video_idl();

}  // namespace wysiwyf::io::image_codec
