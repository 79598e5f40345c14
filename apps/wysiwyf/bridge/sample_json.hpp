#pragma once
// A sample as DDS carried it (CDR) -> JSON, for the dashboard and `wysiwyf monitor`: decoded as
// the dynamic type of any type this build or a message library describes (message_libraries.hpp)
// and walked as `wysiwyf topic echo` prints it, so the field names and values are echo's.
#include <cstdint>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "wysiwyf/msgs.hpp"

namespace wysiwyf::bridge {

// YAML text (as the message printers write it) -> JSON: numbers, true/false, strings; maps and
// sequences nested.
nlohmann::json yaml_to_json(const std::string& yaml);

// The value at a dotted path ("wrench.force.z", "position.2") of a JSON sample, if it is a number.
std::optional<double> number_at(const nlohmann::json& sample, const std::string& path);

class SampleDecoder {
 public:
  SampleDecoder();
  ~SampleDecoder();
  // The sample as JSON; nullopt if no type description is found or the bytes do not decode.
  std::optional<nlohmann::json> to_json(const std::string& type_name, const std::vector<std::uint8_t>& cdr);
  // An Image sample (valid until the next call), for the pixels; nullptr if it does not decode.
  const msg::Image* image(const std::vector<std::uint8_t>& cdr);

 private:
  struct Decoder;
  std::map<std::string, std::unique_ptr<Decoder>> decoders_;  // null: no description found
  msg::Image image_;
};

}  // namespace wysiwyf::bridge
