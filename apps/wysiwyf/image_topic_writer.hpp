#pragma once
// `wysiwyf record --images lossless|video`: one Image topic's samples into the file, each packed
// as a foxglove CompressedImage or CompressedVideo (libs/io/image_codec) where that makes the
// file smaller, else as recorded. The topic's first image decides: with video, an image that
// goes into a video (8-bit colour or grey, float depth) and that zstd (the chunks' compression)
// does not bring under kRawShareVideo is an H.264 stream; otherwise one that zstd does not bring
// under kRawShare is packed losslessly; the rest (rendered and synthetic images: a codec would
// save little at ten times the cost) stays raw. Channels are made as the samples come, on the
// writer thread: a packed channel for the first image's shape, a raw one for any sample that
// cannot be packed (another shape, a stamp outside foxglove.Time, a corrupt sample). Packing is
// split from writing so that the recorder packs several topics' images at once.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "image_codec/recorded_image.hpp"
#include "mcap/mcap_writer.hpp"

namespace wysiwyf::cli {

class ImageTopicWriter {
 public:
  static constexpr double kRawShare = 0.05, kRawShareVideo = 0.01;

  // `schema_name` / `schema_idl`: the topic type's schema ("" where there is none); `metadata`:
  // what every channel of the topic carries (dds_type, QoS); `video`: lossy H.264 where it applies.
  ImageTopicWriter(std::string topic, std::string schema_name, std::string schema_idl,
                   io::image_codec::Metadata metadata, bool video);

  // An image as the file will hold it: packed (bytes), or raw (bytes empty; problem says why
  // where it could not be packed).
  struct Packed {
    std::vector<std::uint8_t> bytes;
    std::uint32_t seq = 0;
    std::size_t pixel_bytes = 0;
    std::string problem;
  };
  // Packs the topic's next sample. One thread at a time per topic, in the samples' order (a video
  // stream's state); topics in parallel. Touches no file.
  void pack(const std::vector<std::uint8_t>& cdr, Packed& out);
  // Writes the sample as pack() made it, with the writer locked (channels as they are needed).
  void write(io::mcap::Writer& writer, std::uint32_t sequence, std::uint64_t log_ns, std::uint64_t publish_ns,
             const std::vector<std::uint8_t>& cdr, const Packed& packed);

  // One line for the recorder's summary: how the topic was kept.
  std::string summary() const;

 private:
  std::uint16_t raw_channel(io::mcap::Writer& writer);
  void decide(const io::image_codec::ImageSample& first);

  std::string topic_, schema_name_, schema_idl_;
  io::image_codec::Metadata metadata_;
  bool video_;
  std::unique_ptr<io::image_codec::VideoEncoder> encoder_;  // kH264
  float depth_max_ = 0;                                     // kH264 of 32FC1
  std::optional<io::image_codec::Packing> packing_;         // decided by the first image
  io::image_codec::Shape shape_;
  std::uint16_t packed_channel_ = 0, raw_channel_ = 0;
  io::image_codec::ImageSample image_;  // (reused)
  std::uint64_t packed_count_ = 0, raw_count_ = 0, pixel_bytes_ = 0, packed_bytes_ = 0;
  std::string first_problem_;
};

}  // namespace wysiwyf::cli
