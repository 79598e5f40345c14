#include "image_topic_writer.hpp"

#include <cmath>
#include <iostream>

namespace wysiwyf::cli {

namespace ic = io::image_codec;

ImageTopicWriter::ImageTopicWriter(std::string topic, std::string schema_name, std::string schema_idl,
                                   ic::Metadata metadata)
    : topic_(std::move(topic)),
      schema_name_(std::move(schema_name)),
      schema_idl_(std::move(schema_idl)),
      metadata_(std::move(metadata)) {}

std::uint16_t ImageTopicWriter::raw_channel(io::mcap::Writer& writer) {
  if (raw_channel_ == 0) {
    const std::uint16_t schema = schema_name_.empty() ? 0 : writer.add_schema(schema_name_, "omgidl", schema_idl_);
    raw_channel_ = writer.add_channel(schema, topic_, "cdr", metadata_);
  }
  return raw_channel_;
}

void ImageTopicWriter::write(io::mcap::Writer& writer, std::uint32_t sequence, std::uint64_t log_ns,
                             std::uint64_t publish_ns, const std::vector<std::uint8_t>& cdr) {
  std::string problem = ic::parse_image(cdr.data(), cdr.size(), image_);
  if (problem.empty() && !packing_) {  // the first image decides
    packing_ = ic::lossless_packing(image_);
    if (*packing_ != ic::Packing::kRaw && ic::zstd_share(image_) < kRawShare) packing_ = ic::Packing::kRaw;
    shape_ = ic::shape_of(image_);
  }
  if (problem.empty() && *packing_ != ic::Packing::kRaw) {
    problem = ic::unpackable(image_, shape_, *packing_);
    if (problem.empty()) problem = ic::pack(image_, *packing_, packed_);
    if (problem.empty()) {
      if (packed_channel_ == 0) {
        const std::uint16_t schema = writer.add_schema(ic::kCompressedImageName, "omgidl", ic::compressed_image_idl());
        ic::Metadata m = metadata_;
        m.merge(ic::packed_metadata(shape_, *packing_));
        packed_channel_ = writer.add_channel(schema, topic_, "cdr", m);
      }
      writer.write(packed_channel_, static_cast<std::uint32_t>(image_.seq), log_ns, publish_ns, packed_.data(),
                   packed_.size());
      ++packed_count_;
      pixel_bytes_ += image_.data.size();
      packed_bytes_ += packed_.size();
      return;
    }
  }
  if (!problem.empty() && first_problem_.empty()) {
    first_problem_ = problem;
    std::cerr << "topic '" << topic_ << "': an image recorded as it came (not packed): " << problem << "\n";
  }
  writer.write(raw_channel(writer), sequence, log_ns, publish_ns, cdr.data(), cdr.size());
  ++raw_count_;
}

std::string ImageTopicWriter::summary() const {
  if (packed_count_ == 0) return "raw";
  std::string s = ic::packing_name(*packing_) + ", " +
                  std::to_string(std::lround(100.0 * static_cast<double>(packed_bytes_) /
                                             static_cast<double>(std::max<std::uint64_t>(pixel_bytes_, 1)))) +
                  " % of the pixels";
  if (raw_count_) s += "; " + std::to_string(raw_count_) + " raw (" + first_problem_ + ")";
  return s;
}

}  // namespace wysiwyf::cli
