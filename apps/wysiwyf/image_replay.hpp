#pragma once
// `wysiwyf play`'s side of `record --images`: the messages of a packed image channel turned back
// into the Image samples that were recorded (libs/io/image_codec), before they are published or
// fed. A message that does not decode (corrupt, truncated, another size than its channel says)
// is skipped with a reason; replay goes on with the next.
#include <cstdint>
#include <map>
#include <ostream>
#include <string>
#include <vector>

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
  std::vector<std::uint8_t> image_;  // (reused)
};

}  // namespace wysiwyf::cli
