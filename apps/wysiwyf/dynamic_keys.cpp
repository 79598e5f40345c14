#include "dynamic_keys.hpp"

#include <fastrtps/types/DynamicData.h>
#include <fastrtps/types/DynamicDataFactory.h>
#include <fastrtps/types/DynamicPubSubType.h>
#include <fastrtps/types/DynamicTypePtr.h>

#include <cstring>
#include <memory>
#include <mutex>

#include "message_libraries.hpp"

namespace wysiwyf::cli {

namespace types = eprosima::fastrtps::types;
using eprosima::fastrtps::rtps::InstanceHandle_t;
using eprosima::fastrtps::rtps::SerializedPayload_t;

namespace {

// One type's support and a sample to decode into, reused for every sample (a writer computes
// keys on its own thread, one sample at a time; the mutex keeps it so).
struct KeyState {
  explicit KeyState(types::DynamicType_ptr t) : type(std::move(t)), support(type) {
    data = types::DynamicDataFactory::get_instance()->create_data(type);
  }
  ~KeyState() { types::DynamicDataFactory::get_instance()->delete_data(data); }
  KeyState(const KeyState&) = delete;
  KeyState& operator=(const KeyState&) = delete;

  types::DynamicType_ptr type;
  types::DynamicPubSubType support;
  types::DynamicData* data = nullptr;
  std::mutex mutex;
};

}  // namespace

RawCdrType::KeyOf dynamic_key_of(const std::string& type_name, std::string& searched) {
  types::DynamicType_ptr type;
  if (!find_dynamic_type(type_name, type, searched)) return {};
  auto state = std::make_shared<KeyState>(type);
  if (!state->data) return {};
  return [state](const std::vector<std::uint8_t>& cdr, InstanceHandle_t* handle, bool force_md5) {
    if (cdr.size() < 4) return false;
    std::lock_guard<std::mutex> lock(state->mutex);
    SerializedPayload_t payload(static_cast<std::uint32_t>(cdr.size()));
    std::memcpy(payload.data, cdr.data(), cdr.size());
    payload.length = static_cast<std::uint32_t>(cdr.size());
    try {
      return state->support.deserialize(&payload, state->data) && state->support.getKey(state->data, handle, force_md5);
    } catch (...) {  // bytes that are not this type
      return false;
    }
  };
}

}  // namespace wysiwyf::cli
