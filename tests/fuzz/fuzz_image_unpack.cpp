// libFuzzer target: what `wysiwyf play` does with a packed image from a file (scripts/fuzz images):
// arbitrary bytes as an Image sample's CDR, as a CompressedImage / CompressedVideo message, and as
// the compressed data of each packing (WebP, the depth PNG, an H.264 colour and a depth stream)
// on a channel of a fixed shape. Each is decoded or refused with a reason; nothing reads out of
// bounds, crashes or allocates for a size the bytes claim; what decodes has the channel's shape.
// The first input byte picks the channel. With WYSIWYF_FUZZ_SEEDS=DIR the target first writes a
// valid message of each kind there (the seeds scripts/fuzz starts from).
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <string>

#include "image_codec/image_cdr.hpp"
#include "image_codec/recorded_image.hpp"

using namespace wysiwyf::io::image_codec;

namespace {

constexpr int kChannels = 4;

ImageSample sample(const std::string& encoding) {
  ImageSample im;
  im.width = 32, im.height = 16, im.encoding = encoding, im.stamp_ns = 7, im.frame_id = "f";
  im.step = im.width * (encoding == "32FC1" ? 4 : 3);
  im.data.resize(std::size_t{im.step} * im.height);
  for (std::size_t i = 0; i < im.data.size(); ++i) im.data[i] = static_cast<std::uint8_t>(i * 37 / 5);
  if (encoding == "32FC1")
    for (std::size_t i = 0; i < im.data.size(); i += 4) {
      const float d = 0.5f + 0.001f * static_cast<float>(i);
      std::memcpy(im.data.data() + i, &d, 4);
    }
  return im;
}

struct Channel {
  Metadata metadata;
  std::size_t pixels;
};

const Channel& channel(int i) {
  static const Channel channels[kChannels] = {
      {packed_metadata(shape_of(sample("rgb8")), Packing::kWebp), 32 * 16 * 3},
      {packed_metadata(shape_of(sample("32FC1")), Packing::kFloatDeltaPng), 32 * 16 * 4},
      {packed_metadata(shape_of(sample("rgb8")), Packing::kH264), 32 * 16 * 3},
      {packed_metadata(shape_of(sample("32FC1")), Packing::kH264, 1.0f), 32 * 16 * 4}};
  return channels[i];
}

void write_seeds(const std::string& dir) {
  for (int i = 0; i < kChannels; ++i) {
    const ImageSample im = sample(i % 2 ? "32FC1" : "rgb8");
    std::vector<std::uint8_t> cdr;
    if (i < 2) {
      if (!pack(im, i == 0 ? Packing::kWebp : Packing::kFloatDeltaPng, cdr).empty()) std::abort();
    } else {
      VideoEncoder encoder(shape_of(im), 1.0f);
      if (!pack_video(im, encoder, cdr).empty()) std::abort();
    }
    CompressedFrame frame;
    if (!parse_compressed(cdr.data(), cdr.size(), frame).empty()) std::abort();
    std::ofstream(dir + "/seed_data_" + std::to_string(i))
        .put(static_cast<char>(i))
        .write(reinterpret_cast<const char*>(frame.data.data()), static_cast<std::streamsize>(frame.data.size()));
    std::ofstream(dir + "/seed_message_" + std::to_string(i))
        .put(static_cast<char>(i + kChannels))
        .write(reinterpret_cast<const char*>(cdr.data()), static_cast<std::streamsize>(cdr.size()));
  }
  const std::vector<std::uint8_t> image = image_cdr(sample("rgb8"));
  std::ofstream(dir + "/seed_image")
      .put(0)
      .write(reinterpret_cast<const char*>(image.data()), static_cast<std::streamsize>(image.size()));
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  if (const char* dir = std::getenv("WYSIWYF_FUZZ_SEEDS")) write_seeds(dir);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const int pick = data[0] % (2 * kChannels);
  const Channel& ch = channel(pick % kChannels);
  ++data, --size;
  ImageSample image;
  if (parse_image(data, size, image).empty() && image_cdr(image) != std::vector<std::uint8_t>(data, data + size))
    std::abort();  // what parses writes back to the same bytes
  std::vector<std::uint8_t> message(data, data + size), out;
  if (pick < kChannels) {  // the bytes as the compressed data of a well-formed message
    CompressedFrame frame;
    frame.format = pick == 0 ? "webp" : pick == 1 ? "png" : "h264";
    frame.data.assign(data, data + size);
    message = compressed_cdr(frame);
  }
  std::unique_ptr<VideoDecoder> video;  // (a fresh stream each input: the runs do not depend on order)
  if (unpack(ch.metadata, 1, message.data(), message.size(), out, video).empty()) {
    ImageSample back;
    if (!parse_image(out.data(), out.size(), back).empty() || back.data.size() != ch.pixels) std::abort();
  }
  return 0;
}
