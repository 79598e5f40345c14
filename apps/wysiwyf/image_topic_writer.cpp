#include "image_topic_writer.hpp"

#include <algorithm>
#include <cstdio>
#include <iostream>

namespace wysiwyf::cli {

namespace ic = io::image_codec;

ImageTopicWriter::ImageTopicWriter(std::string topic, std::string schema_name, std::string schema_idl,
                                   ic::Metadata metadata, bool video)
    : topic_(std::move(topic)),
      schema_name_(std::move(schema_name)),
      schema_idl_(std::move(schema_idl)),
      metadata_(std::move(metadata)),
      video_(video) {}

void ImageTopicWriter::decide(const ic::ImageSample& first) {
  shape_ = ic::shape_of(first);
  const double share = ic::zstd_share(first);
  packing_ = ic::Packing::kRaw;
  if (video_ && ic::video_problem(shape_).empty() && share >= kRawShareVideo) {
    try {
      if (first.encoding == "32FC1") depth_max_ = ic::depth_max_for(first);
      encoder_ = std::make_unique<ic::VideoEncoder>(shape_, depth_max_);
      packing_ = ic::Packing::kH264;
      return;
    } catch (const std::exception& e) {  // (a libavcodec without libx264): lossless instead
      std::cerr << "topic '" << topic_ << "': no video: " << e.what() << "\n";
    }
  }
  if (ic::lossless_packing(first) != ic::Packing::kRaw && share >= kRawShare) packing_ = ic::lossless_packing(first);
}

std::uint16_t ImageTopicWriter::raw_channel(io::mcap::Writer& writer) {
  if (raw_channel_ == 0) {
    const std::uint16_t schema = schema_name_.empty() ? 0 : writer.add_schema(schema_name_, "omgidl", schema_idl_);
    raw_channel_ = writer.add_channel(schema, topic_, "cdr", metadata_);
  }
  return raw_channel_;
}

void ImageTopicWriter::pack(const std::vector<std::uint8_t>& cdr, Packed& out) {
  out.bytes.clear();
  out.problem = ic::parse_image(cdr.data(), cdr.size(), image_);
  if (out.problem.empty() && !packing_) decide(image_);  // the first image decides
  if (!out.problem.empty() || *packing_ == ic::Packing::kRaw) return;
  out.problem = ic::unpackable(image_, shape_, *packing_);
  if (out.problem.empty())
    out.problem = *packing_ == ic::Packing::kH264 ? ic::pack_video(image_, *encoder_, out.bytes)
                                                  : ic::pack(image_, *packing_, out.bytes);
  if (!out.problem.empty()) out.bytes.clear();
  out.seq = static_cast<std::uint32_t>(image_.seq);
  out.pixel_bytes = image_.data.size();
}

void ImageTopicWriter::write(io::mcap::Writer& writer, std::uint32_t sequence, std::uint64_t log_ns,
                             std::uint64_t publish_ns, const std::vector<std::uint8_t>& cdr, const Packed& packed) {
  if (!packed.bytes.empty()) {
    if (packed_channel_ == 0) {
      const bool video = *packing_ == ic::Packing::kH264;
      const std::uint16_t schema =
          video ? writer.add_schema(ic::kCompressedVideoName, "omgidl", ic::compressed_video_idl())
                : writer.add_schema(ic::kCompressedImageName, "omgidl", ic::compressed_image_idl());
      ic::Metadata m = metadata_;
      m.merge(ic::packed_metadata(shape_, *packing_, depth_max_));
      packed_channel_ = writer.add_channel(schema, topic_, "cdr", m);
    }
    writer.write(packed_channel_, packed.seq, log_ns, publish_ns, packed.bytes.data(), packed.bytes.size());
    ++packed_count_;
    pixel_bytes_ += packed.pixel_bytes;
    packed_bytes_ += packed.bytes.size();
    return;
  }
  if (!packed.problem.empty() && first_problem_.empty()) {
    first_problem_ = packed.problem;
    std::cerr << "topic '" << topic_ << "': an image recorded as it came (not packed): " << packed.problem << "\n";
  }
  writer.write(raw_channel(writer), sequence, log_ns, publish_ns, cdr.data(), cdr.size());
  ++raw_count_;
}

std::string ImageTopicWriter::summary() const {
  if (packed_count_ == 0) return "raw";
  char figures[96];
  std::snprintf(
      figures, sizeof(figures), ", %.1f MB, %.1f %% of the pixels", static_cast<double>(packed_bytes_) / 1e6,
      100.0 * static_cast<double>(packed_bytes_) / static_cast<double>(std::max<std::uint64_t>(pixel_bytes_, 1)));
  std::string s = ic::packing_name(*packing_) + figures;
  if (raw_count_) s += "; " + std::to_string(raw_count_) + " raw (" + first_problem_ + ")";
  return s;
}

}  // namespace wysiwyf::cli
