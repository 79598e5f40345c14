#pragma once
// `wysiwyf record --images lossless`: one Image topic's samples into the file, each packed as a
// foxglove CompressedImage (libs/io/image_codec) where that makes the file smaller, else as
// recorded. The topic's first image decides: an image whose pixels zstd (the chunks'
// compression) already brings under kRawShare stays raw (rendered and synthetic images: the
// codec would save little at ten times the cost). Channels are made as the samples come, on the
// writer thread: a packed channel for the first image's shape, a raw one for any sample that
// cannot be packed (another shape, a stamp outside foxglove.Time, a corrupt sample).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "image_codec/recorded_image.hpp"
#include "mcap/mcap_writer.hpp"

namespace wysiwyf::cli {

class ImageTopicWriter {
 public:
  static constexpr double kRawShare = 0.05;

  // `schema_name` / `schema_idl`: the topic type's schema ("" where there is none); `metadata`:
  // what every channel of the topic carries (dds_type, QoS).
  ImageTopicWriter(std::string topic, std::string schema_name, std::string schema_idl,
                   io::image_codec::Metadata metadata);

  // On the writer thread, with the writer locked.
  void write(io::mcap::Writer& writer, std::uint32_t sequence, std::uint64_t log_ns, std::uint64_t publish_ns,
             const std::vector<std::uint8_t>& cdr);

  // One line for the recorder's summary: how the topic was kept.
  std::string summary() const;

 private:
  std::uint16_t raw_channel(io::mcap::Writer& writer);

  std::string topic_, schema_name_, schema_idl_;
  io::image_codec::Metadata metadata_;
  std::optional<io::image_codec::Packing> packing_;  // decided by the first image
  io::image_codec::Shape shape_;
  std::uint16_t packed_channel_ = 0, raw_channel_ = 0;
  io::image_codec::ImageSample image_;  // (reused)
  std::vector<std::uint8_t> packed_;    // (reused)
  std::uint64_t packed_count_ = 0, raw_count_ = 0, pixel_bytes_ = 0, packed_bytes_ = 0;
  std::string first_problem_;
};

}  // namespace wysiwyf::cli
