#include "image_replay.hpp"

#include <iostream>

#include "image_codec/recorded_image.hpp"

namespace wysiwyf::cli {

bool ImageReplay::unpack(const io::mcap::Channel& ch, io::mcap::Message& m) {
  if (!io::image_codec::is_packed(ch.metadata)) return true;
  const std::string why =
      io::image_codec::unpack(ch.metadata, m.sequence, m.data.data(), m.data.size(), image_, video_[ch.id]);
  if (why.empty()) {
    m.data.swap(image_);
    return true;
  }
  Skipped& s = skipped_[ch.topic];
  if (s.count++ == 0) {
    s.first = why;
    std::cerr << "topic '" << ch.topic << "': a recorded image skipped (at log time " << m.log_time << " ns): " << why
              << "\n";
  }
  return false;
}

void ImageReplay::report(std::ostream& out) const {
  for (const auto& [topic, s] : skipped_)
    out << "  not played on '" << topic << "': " << s.count << " image(s) that do not decode; the first: " << s.first
        << "\n";
}

std::uint64_t ImageReplay::skipped() const {
  std::uint64_t n = 0;
  for (const auto& [topic, s] : skipped_) n += s.count;
  return n;
}

}  // namespace wysiwyf::cli
