#pragma once
// `wysiwyf play`'s side of `record --images`: the messages of a packed image channel turned back
// into the Image samples that were recorded (libs/io/image_codec), before they are published or
// fed: bit for bit from a lossless packing, the same samples with approximate pixels from a video. A message that does not decode (corrupt, truncated, another size than its channel says)
// is skipped with a reason; replay goes on with the next.
#include <cstdint>
#include <map>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "image_codec/video.hpp"
#include "mcap/mcap_reader.hpp"

namespace wysiwyf::cli {

class ImageReplay {
 public:
  // Replaces m.data by the Image sample where `ch` is a packed channel; true, or false where it
  // cannot be decoded (the message is to be skipped; the first reason per topic goes to stderr).
  // Messages of other channels pass as they are.
  bool unpack(const io::mcap::Channel& ch, io::mcap::Message& m);
  // One line per topic with skipped messages: how many, and the first reason.
  void report(std::ostream& out) const;
  std::uint64_t skipped() const;

 private:
  struct Skipped {
    std::uint64_t count = 0;
    std::string first;
  };
  std::map<std::string, Skipped> skipped_;
  std::map<std::uint16_t, std::unique_ptr<io::image_codec::VideoDecoder>> video_;  // by channel
  std::vector<std::uint8_t> image_;                                                // (reused)
};

}  // namespace wysiwyf::cli
