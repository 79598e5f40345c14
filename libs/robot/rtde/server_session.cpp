#include "rtde/server_session.hpp"

#include "rtde/variables.hpp"

namespace wysiwyf::robot::rtde {

bool InputOwners::claim(const void* owner, const std::vector<std::string>& names) {
  for (const auto& n : names)
    if (held_by_other(owner, n)) return false;
  for (const auto& n : names) owner_[n] = owner;
  return true;
}

void InputOwners::release(const void* owner) {
  for (auto it = owner_.begin(); it != owner_.end();) it = it->second == owner ? owner_.erase(it) : std::next(it);
}

bool InputOwners::held_by_other(const void* owner, const std::string& name) const {
  const auto it = owner_.find(name);
  return it != owner_.end() && it->second != owner;
}

ServerSession::ServerSession(ControllerVersion version, InputOwners& owners) : version_(version), owners_(owners) {}

ServerSession::~ServerSession() { owners_.release(this); }

void ServerSession::refuse(const std::string& why, std::vector<std::uint8_t>& out) {
  ++refused_;
  last_refusal_ = why;
  encode_text_message(out, {why, "RTDE", MessageLevel::kError});
}

void ServerSession::handle(const RawPackage& pkg, std::vector<std::uint8_t>& out) {
  const auto type = package_type(pkg.type);
  if (!type) return refuse("unknown package type " + std::to_string(pkg.type), out);
  switch (*type) {
    case PackageType::kRequestProtocolVersion: {
      const auto v = decode_request_protocol_version(pkg.payload, pkg.size);
      if (!v) return refuse("malformed RTDE_REQUEST_PROTOCOL_VERSION", out);
      version_agreed_ = *v == kProtocolVersion;
      return encode_accepted(out, *type, version_agreed_);
    }
    case PackageType::kGetUrcontrolVersion:
      if (pkg.size != 0) return refuse("RTDE_GET_URCONTROL_VERSION with a payload", out);
      return encode_urcontrol_version(out, version_);
    case PackageType::kSetupOutputs: return setup_outputs(pkg, out);
    case PackageType::kSetupInputs: return setup_inputs(pkg, out);
    case PackageType::kStart:
      if (pkg.size != 0) return refuse("RTDE_CONTROL_PACKAGE_START with a payload", out);
      streaming_ = version_agreed_ && (output_recipe_ || !inputs_.empty());
      return encode_accepted(out, *type, streaming_);
    case PackageType::kPause:
      if (pkg.size != 0) return refuse("RTDE_CONTROL_PACKAGE_PAUSE with a payload", out);
      streaming_ = false;
      return encode_accepted(out, *type, true);
    case PackageType::kDataPackage: return data(pkg, out);
    case PackageType::kTextMessage:
      if (!decode_text_message(pkg.payload, pkg.size)) return refuse("malformed RTDE_TEXT_MESSAGE", out);
      return;  // a client's message is only read
  }
}

void ServerSession::setup_outputs(const RawPackage& pkg, std::vector<std::uint8_t>& out) {
  if (!version_agreed_) return refuse("output setup before protocol version 2 was agreed", out);
  if (streaming_) return refuse("output setup while streaming (pause first)", out);
  const auto request = decode_setup_outputs(pkg.payload, pkg.size);
  if (!request) return refuse("malformed output setup (frequency in (0, 500] Hz, names [A-Za-z0-9_])", out);
  SetupReply reply;
  std::vector<FieldType> types;
  bool all_found = true;
  for (const auto& name : request->names) {
    const auto t = output_type(name);
    all_found = all_found && t.has_value();
    reply.types.push_back(t ? to_string(*t) : std::string(kNotFound));
    if (t) types.push_back(*t);
  }
  if (all_found) {
    reply.recipe_id = next_id_++;
    output_recipe_ = std::make_unique<Recipe>(reply.recipe_id, request->names, types);
    outputs_ = std::make_unique<RecipeValues>(*output_recipe_);
    output_frequency_ = request->frequency;
  }
  encode_setup_reply(out, PackageType::kSetupOutputs, reply);
}

void ServerSession::setup_inputs(const RawPackage& pkg, std::vector<std::uint8_t>& out) {
  if (!version_agreed_) return refuse("input setup before protocol version 2 was agreed", out);
  if (streaming_) return refuse("input setup while streaming (pause first)", out);
  const auto names = decode_setup_inputs(pkg.payload, pkg.size);
  if (!names) return refuse("malformed input setup (names [A-Za-z0-9_], comma-separated)", out);
  SetupReply reply;
  std::vector<FieldType> types;
  bool usable = true;
  for (const auto& name : *names) {
    const auto t = input_type(name);
    const bool in_use = t && owners_.held_by_other(this, name);
    usable = usable && t && !in_use;
    reply.types.push_back(!t ? std::string(kNotFound) : in_use ? std::string(kInUse) : to_string(*t));
    if (t) types.push_back(*t);
  }
  if (usable && owners_.claim(this, *names)) {
    reply.recipe_id = next_id_++;
    Input input;
    input.recipe = std::make_unique<Recipe>(reply.recipe_id, *names, types);
    input.values = std::make_unique<RecipeValues>(*input.recipe);
    inputs_.push_back(std::move(input));
  }
  encode_setup_reply(out, PackageType::kSetupInputs, reply);
}

void ServerSession::data(const RawPackage& pkg, std::vector<std::uint8_t>& out) {
  if (pkg.size == 0) return refuse("data package without a recipe id", out);
  for (Input& input : inputs_) {
    if (input.recipe->id() != pkg.payload[0]) continue;
    if (!input.values->read(pkg.payload, pkg.size))
      return refuse("data package of recipe " + std::to_string(pkg.payload[0]) + " is " + std::to_string(pkg.size) +
                        " bytes or has a BOOL other than 0 or 1; expected " +
                        std::to_string(1 + input.recipe->values_size()),
                    out);
    ++input_packages_;
    return;
  }
  refuse("data package of recipe " + std::to_string(pkg.payload[0]) + ", which is no input recipe of this connection",
         out);
}

const RecipeValues* ServerSession::inputs(std::uint8_t id) const {
  for (const Input& input : inputs_)
    if (input.recipe->id() == id) return input.values.get();
  return nullptr;
}

void ServerSession::encode_outputs(std::vector<std::uint8_t>& out) const {
  if (outputs_) encode_data_package(out, *outputs_);
}

}  // namespace wysiwyf::robot::rtde
