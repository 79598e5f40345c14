#pragma once
// A sample as DDS carried it (CDR) -> JSON, for the dashboard: decoded with the type support of
// a type this build knows (interfaces/msgs, the kernel's Diagnostics) and walked through its YAML
// printer, so the page sees the same field names as `wysiwyf topic echo` prints.
#include <cstdint>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace eprosima::fastdds::dds {
class TopicDataType;
}

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
  // Whether this build can decode `type_name`.
  bool knows(const std::string& type_name) const;
  // The sample as JSON; nullopt if the type is unknown or the bytes do not decode.
  std::optional<nlohmann::json> to_json(const std::string& type_name, const std::vector<std::uint8_t>& cdr);
  // The decoded sample itself (valid until the next call for this type), for typed uses (images).
  const void* decode(const std::string& type_name, const std::vector<std::uint8_t>& cdr);

 private:
  struct Decoder;
  std::map<std::string, std::unique_ptr<Decoder>> decoders_;
};

}  // namespace wysiwyf::bridge
