#include "sample_json.hpp"

#include <fastdds/dds/topic/TopicDataType.hpp>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstring>

#include "wysiwyf/msgs.hpp"

namespace wysiwyf::bridge {

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
  const MessageType* type = nullptr;
  std::unique_ptr<eprosima::fastdds::dds::TopicDataType> support;
  void* sample = nullptr;
  eprosima::fastrtps::rtps::SerializedPayload_t payload;
  ~Decoder() {
    if (sample) support->deleteData(sample);
  }
};

SampleDecoder::SampleDecoder() = default;
SampleDecoder::~SampleDecoder() = default;

bool SampleDecoder::knows(const std::string& type_name) const { return msgs::registry().find(type_name) != nullptr; }

const void* SampleDecoder::decode(const std::string& type_name, const std::vector<std::uint8_t>& cdr) {
  auto& d = decoders_[type_name];
  if (!d) {
    const MessageType* type = msgs::registry().find(type_name);
    if (!type) return nullptr;
    d = std::make_unique<Decoder>();
    d->type = type;
    d->support.reset(type->make_type());
    d->sample = d->support->createData();
  }
  if (!d->type || cdr.size() < 4) return nullptr;
  if (d->payload.max_size < cdr.size()) d->payload.reserve(static_cast<std::uint32_t>(cdr.size()));
  std::memcpy(d->payload.data, cdr.data(), cdr.size());
  d->payload.length = static_cast<std::uint32_t>(cdr.size());
  d->payload.pos = 0;
  try {
    if (!d->support->deserialize(&d->payload, d->sample)) return nullptr;
  } catch (...) {  // bytes that are not this type
    return nullptr;
  }
  return d->sample;
}

std::optional<nlohmann::json> SampleDecoder::to_json(const std::string& type_name,
                                                     const std::vector<std::uint8_t>& cdr) {
  const void* sample = decode(type_name, cdr);
  if (!sample) return std::nullopt;
  try {
    return yaml_to_json(decoders_[type_name]->type->to_yaml(sample));
  } catch (const YAML::Exception&) {
    return std::nullopt;
  }
}

}  // namespace wysiwyf::bridge
