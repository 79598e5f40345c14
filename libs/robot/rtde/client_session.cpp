#include "rtde/client_session.hpp"

#include <stdexcept>

namespace wysiwyf::robot::rtde {

const char* to_string(ClientSession::State state) {
  switch (state) {
    case ClientSession::State::kIdle: return "idle";
    case ClientSession::State::kVersion: return "asking the protocol version";
    case ClientSession::State::kControllerVersion: return "asking the controller version";
    case ClientSession::State::kOutputs: return "setting up the outputs";
    case ClientSession::State::kInputs: return "setting up the inputs";
    case ClientSession::State::kStart: return "starting";
    case ClientSession::State::kStreaming: return "streaming";
    case ClientSession::State::kFailed: return "failed";
  }
  return "unknown";
}

ClientSession::ClientSession(double frequency, std::vector<Variable> outputs, std::vector<Variable> inputs)
    : frequency_(frequency), asked_outputs_(std::move(outputs)), asked_inputs_(std::move(inputs)) {
  if (asked_outputs_.empty()) throw std::invalid_argument("RTDE client: no output variable asked for");
  // Recipes of id 0 until the controller gives theirs, so that the values exist from the start.
  const auto make = [](const std::vector<Variable>& vars, std::unique_ptr<Recipe>& recipe,
                       std::unique_ptr<RecipeValues>& values) {
    std::vector<std::string> names;
    std::vector<FieldType> types;
    for (const auto& v : vars) names.push_back(v.name), types.push_back(v.type);
    recipe = std::make_unique<Recipe>(0, names, types);
    values = std::make_unique<RecipeValues>(*recipe);
  };
  make(asked_outputs_, output_recipe_, outputs_);
  make(asked_inputs_, input_recipe_, inputs_);
}

void ClientSession::begin(std::vector<std::uint8_t>& out) {
  state_ = State::kVersion;
  error_.clear();
  encode_request_protocol_version(out, kProtocolVersion);
}

void ClientSession::fail(const std::string& why) {
  state_ = State::kFailed;
  error_ = why;
}

void ClientSession::refuse(const std::string& why) {
  ++refused_;
  last_refusal_ = why;
}

bool ClientSession::take_setup(const RawPackage& pkg, const std::vector<Variable>& asked, const char* what,
                               std::unique_ptr<Recipe>& recipe, std::unique_ptr<RecipeValues>& values) {
  const auto reply = decode_setup_reply(pkg.payload, pkg.size);
  if (!reply || reply->types.size() != asked.size()) {
    fail(std::string("malformed ") + what + " setup reply");
    return false;
  }
  std::vector<std::string> names;
  std::vector<FieldType> types;
  for (std::size_t i = 0; i < asked.size(); ++i) {
    if (field_type(reply->types[i]) != asked[i].type) {
      fail(std::string(what) + " variable '" + asked[i].name + "': the controller says " + reply->types[i] +
           ", expected " + to_string(asked[i].type));
      return false;
    }
    names.push_back(asked[i].name);
    types.push_back(asked[i].type);
  }
  if (reply->recipe_id == 0) {
    fail(std::string("the controller refused the ") + what + " recipe (recipe id 0)");
    return false;
  }
  recipe = std::make_unique<Recipe>(reply->recipe_id, names, types);
  values = std::make_unique<RecipeValues>(*recipe);
  return true;
}

bool ClientSession::handle(const RawPackage& pkg, std::vector<std::uint8_t>& out) {
  const auto type = package_type(pkg.type);
  if (!type) {
    refuse("unknown package type " + std::to_string(pkg.type));
    return false;
  }
  if (*type == PackageType::kTextMessage) {
    if (auto m = decode_text_message(pkg.payload, pkg.size)) {
      last_message_ = std::move(*m);
      ++messages_;
    } else {
      refuse("malformed RTDE_TEXT_MESSAGE");
    }
    return false;
  }
  switch (state_) {
    case State::kVersion: {
      const auto accepted =
          *type == PackageType::kRequestProtocolVersion ? decode_accepted(pkg.payload, pkg.size) : std::nullopt;
      if (!accepted) break;
      if (!*accepted) {
        fail("the controller refused RTDE protocol version 2 (a controller before software 3.5?)");
        return false;
      }
      state_ = State::kControllerVersion;
      encode_get_urcontrol_version(out);
      return false;
    }
    case State::kControllerVersion: {
      const auto v =
          *type == PackageType::kGetUrcontrolVersion ? decode_urcontrol_version(pkg.payload, pkg.size) : std::nullopt;
      if (!v) break;
      controller_ = *v;
      state_ = State::kOutputs;
      SetupOutputsRequest request{frequency_, {}};
      for (const auto& o : asked_outputs_) request.names.push_back(o.name);
      encode_setup_outputs(out, request);
      return false;
    }
    case State::kOutputs:
      if (*type != PackageType::kSetupOutputs) break;
      if (!take_setup(pkg, asked_outputs_, "output", output_recipe_, outputs_)) return false;
      if (asked_inputs_.empty()) {
        state_ = State::kStart;
        encode_start(out);
      } else {
        state_ = State::kInputs;
        std::vector<std::string> names;
        for (const auto& i : asked_inputs_) names.push_back(i.name);
        encode_setup_inputs(out, names);
      }
      return false;
    case State::kInputs:
      if (*type != PackageType::kSetupInputs) break;
      if (!take_setup(pkg, asked_inputs_, "input", input_recipe_, inputs_)) return false;
      state_ = State::kStart;
      encode_start(out);
      return false;
    case State::kStart: {
      const auto accepted = *type == PackageType::kStart ? decode_accepted(pkg.payload, pkg.size) : std::nullopt;
      if (!accepted) break;
      if (!*accepted) {
        fail("the controller refused to start the stream");
        return false;
      }
      state_ = State::kStreaming;
      return false;
    }
    case State::kStreaming:
      if (*type != PackageType::kDataPackage) break;
      if (!outputs_->read(pkg.payload, pkg.size)) {
        refuse("data package of " + std::to_string(pkg.size) + " bytes or recipe " +
               std::to_string(pkg.size ? pkg.payload[0] : 0) + "; expected " +
               std::to_string(1 + output_recipe_->values_size()) + " of recipe " +
               std::to_string(output_recipe_->id()));
        return false;
      }
      ++data_packages_;
      return true;
    case State::kIdle:
    case State::kFailed: break;
  }
  refuse(std::string(to_string(*type)) + " (" + std::to_string(pkg.size) + " bytes) while " + to_string(state_));
  return false;
}

std::size_t ClientSession::output_index(const std::string& name) const {
  for (std::size_t i = 0; i < asked_outputs_.size(); ++i)
    if (asked_outputs_[i].name == name) return i;
  throw std::invalid_argument("RTDE client: no output variable '" + name + "' was asked for");
}

std::size_t ClientSession::input_index(const std::string& name) const {
  for (std::size_t i = 0; i < asked_inputs_.size(); ++i)
    if (asked_inputs_[i].name == name) return i;
  throw std::invalid_argument("RTDE client: no input variable '" + name + "' was asked for");
}

void ClientSession::encode_inputs(std::vector<std::uint8_t>& out) const {
  if (streaming() && !asked_inputs_.empty()) encode_data_package(out, *inputs_);
}

}  // namespace wysiwyf::robot::rtde
