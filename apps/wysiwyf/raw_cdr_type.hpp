#pragma once
// A DDS type support that keeps samples as the bytes on the wire (CDR with its encapsulation
// header) under any type name: the recorder reads every topic with it and the player writes
// them back, without knowing the types.
#include <fastdds/dds/topic/TopicDataType.hpp>

#include <cstdint>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

namespace wysiwyf::cli {

struct RawCdr {
  std::vector<std::uint8_t> bytes;
};

class RawCdrType final : public eprosima::fastdds::dds::TopicDataType {
 public:
  // A sample's instance from its bytes (dynamic_keys.hpp); false where the bytes are not the type.
  using KeyOf = std::function<bool(const std::vector<std::uint8_t>& cdr,
                                   eprosima::fastrtps::rtps::InstanceHandle_t* handle, bool force_md5)>;

  // `keyed`: the type has @key members (a reader must say so to match its writers).
  // `key_of`: how a writer of a keyed type computes each sample's instance; without it every
  // sample counts as one instance (enough for a reader: a writer sends the key with the sample).
  RawCdrType(const std::string& type_name, bool keyed, KeyOf key_of = {}) : key_of_(std::move(key_of)) {
    setName(type_name.c_str());
    m_typeSize = 64 * 1024;  // a first guess for buffers; larger samples grow them
    m_isGetKeyDefined = keyed;
    // Announced by name only: a tool that registered type objects (its own types', message
    // libraries') would otherwise send them in discovery, and Fast DDS 2.9 participants that
    // receive them crash building their sequence types (a pipeline died when the bridge attached).
    auto_fill_type_object(false);
    auto_fill_type_information(false);
  }
  bool serialize(void* data, eprosima::fastrtps::rtps::SerializedPayload_t* payload) override {
    const auto& b = static_cast<RawCdr*>(data)->bytes;
    if (b.size() < 4) return false;
    if (payload->max_size < b.size()) payload->reserve(static_cast<std::uint32_t>(b.size()));
    std::memcpy(payload->data, b.data(), b.size());
    payload->length = static_cast<std::uint32_t>(b.size());
    payload->encapsulation = b[1] == 0x01 ? CDR_LE : CDR_BE;  // the representation's byte order
    return true;
  }
  bool deserialize(eprosima::fastrtps::rtps::SerializedPayload_t* payload, void* data) override {
    static_cast<RawCdr*>(data)->bytes.assign(payload->data, payload->data + payload->length);
    return true;
  }
  std::function<std::uint32_t()> getSerializedSizeProvider(void* data) override {
    return [data] { return static_cast<std::uint32_t>(static_cast<RawCdr*>(data)->bytes.size()); };
  }
  void* createData() override { return new RawCdr(); }
  void deleteData(void* data) override { delete static_cast<RawCdr*>(data); }
  // Without a key function the bytes are not decoded, so a keyed type's samples all count as one
  // instance: the recorder takes each as it comes (per-instance history does not matter to it).
  bool getKey(void* data, eprosima::fastrtps::rtps::InstanceHandle_t* handle, bool force_md5) override {
    if (!m_isGetKeyDefined) return false;
    if (key_of_) return key_of_(static_cast<RawCdr*>(data)->bytes, handle, force_md5);
    *handle = eprosima::fastrtps::rtps::InstanceHandle_t();
    handle->value[0] = 1;
    return true;
  }

 private:
  KeyOf key_of_;
};

}  // namespace wysiwyf::cli
