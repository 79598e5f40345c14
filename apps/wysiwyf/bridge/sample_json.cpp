#include "sample_json.hpp"

#include <fastdds/dds/topic/TopicDataType.hpp>
#include <fastrtps/types/DynamicTypePtr.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstring>

#include "../cdr_yaml.hpp"
#include "../message_libraries.hpp"
#include "wysiwyf/msgs.hpp"

namespace wysiwyf::bridge {

namespace types = eprosima::fastrtps::types;

namespace {

nlohmann::json node_to_json(const YAML::Node& n) {
  if (n.IsMap()) {
    nlohmann::json out = nlohmann::json::object();
    for (const auto& kv : n) out[kv.first.as<std::string>()] = node_to_json(kv.second);
    return out;
  }
  if (n.IsSequence()) {
    nlohmann::json out = nlohmann::json::array();
    for (const auto& item : n) out.push_back(node_to_json(item));
    return out;
  }
  if (!n.IsScalar()) return nullptr;
  const std::string& s = n.Scalar();
  if (n.Tag() == "!") return s;  // quoted in the YAML: a string even if it reads as a number
  if (s == "true" || s == "false") return s == "true";
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (!s.empty() && end == s.c_str() + s.size()) {
    if (!std::isfinite(v)) return nullptr;  // JSON has no inf or nan
    if (s.find_first_of(".eE") == std::string::npos && std::fabs(v) < 9e15) return static_cast<std::int64_t>(v);
    return v;
  }
  return s;
}

}  // namespace

nlohmann::json yaml_to_json(const std::string& yaml) { return node_to_json(YAML::Load(yaml)); }

std::optional<double> number_at(const nlohmann::json& sample, const std::string& path) {
  const nlohmann::json* at = &sample;
  std::size_t begin = 0;
  while (begin <= path.size()) {
    const std::size_t end = std::min(path.find('.', begin), path.size());
    const std::string part = path.substr(begin, end - begin);
    if (at->is_object()) {
      auto it = at->find(part);
      if (it == at->end()) return std::nullopt;
      at = &*it;
    } else if (at->is_array()) {
      char* stop = nullptr;
      const unsigned long i = std::strtoul(part.c_str(), &stop, 10);
      if (part.empty() || *stop || i >= at->size()) return std::nullopt;
      at = &(*at)[i];
    } else {
      return std::nullopt;
    }
    begin = end + 1;
  }
  if (at->is_number()) return at->get<double>();
  if (at->is_boolean()) return at->get<bool>() ? 1.0 : 0.0;
  return std::nullopt;
}

struct SampleDecoder::Decoder {
  types::DynamicType_ptr type;
};

SampleDecoder::SampleDecoder() = default;
SampleDecoder::~SampleDecoder() = default;

std::optional<nlohmann::json> SampleDecoder::to_json(const std::string& type_name,
                                                     const std::vector<std::uint8_t>& cdr) {
  auto [it, added] = decoders_.try_emplace(type_name);
  if (added) {
    types::DynamicType_ptr type;
    std::string searched;
    if (cli::find_dynamic_type(type_name, type, searched)) it->second = std::make_unique<Decoder>(Decoder{type});
  }
  if (!it->second) return std::nullopt;
  try {
    return yaml_to_json(cli::cdr_to_yaml(cdr.data(), cdr.size(), it->second->type));
  } catch (...) {  // bytes that are not this type
    return std::nullopt;
  }
}

const msg::Image* SampleDecoder::image(const std::vector<std::uint8_t>& cdr) {
  static auto* support = MessageTraits<msg::Image>::make_type();
  if (cdr.size() < 4) return nullptr;
  eprosima::fastrtps::rtps::SerializedPayload_t payload(static_cast<std::uint32_t>(cdr.size()));
  std::memcpy(payload.data, cdr.data(), cdr.size());
  payload.length = static_cast<std::uint32_t>(cdr.size());
  try {
    return support->deserialize(&payload, &image_) ? &image_ : nullptr;
  } catch (...) {
    return nullptr;
  }
}

}  // namespace wysiwyf::bridge
