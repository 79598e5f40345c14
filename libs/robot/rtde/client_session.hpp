#pragma once
// A client's end of one RTDE connection (the driver's): the handshake in the guide's order
// (protocol version 2, the controller's version, the output recipe at its frequency, the input
// recipe, start), each answer checked (a refused version, a variable NOT_FOUND or IN_USE, a type
// other than the one asked for, a refused start: failed, with why), then the stream: each output
// data package read into the output values, each input written from the input values. Sockets
// and timeouts are the caller's.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "rtde/framer.hpp"
#include "rtde/packages.hpp"
#include "rtde/recipe.hpp"

namespace wysiwyf::robot::rtde {

// A variable of a recipe the client asks for, with the type it expects.
struct Variable {
  std::string name;
  FieldType type;
};

class ClientSession {
 public:
  enum class State { kIdle, kVersion, kControllerVersion, kOutputs, kInputs, kStart, kStreaming, kFailed };

  // Throws std::invalid_argument for no outputs, or names a recipe cannot hold (Recipe's rules).
  ClientSession(double frequency, std::vector<Variable> outputs, std::vector<Variable> inputs);

  // Starts the handshake: appends the version request to `out`.
  void begin(std::vector<std::uint8_t>& out);
  // Handles one package from the controller, appending what to send next to `out`. Returns true
  // when it was an output data package (the output values are new).
  bool handle(const RawPackage& pkg, std::vector<std::uint8_t>& out);

  State state() const { return state_; }
  bool streaming() const { return state_ == State::kStreaming; }
  bool failed() const { return state_ == State::kFailed; }
  // Why the handshake failed.
  const std::string& error() const { return error_; }

  const ControllerVersion& controller_version() const { return controller_; }
  // The newest output values (zero until the first data package) and a variable's index in them.
  // Both recipes are replaced when the controller answers their setup: take references anew.
  const RecipeValues& outputs() const { return *outputs_; }
  std::size_t output_index(const std::string& name) const;
  // The input values the next encode_inputs() sends.
  RecipeValues& inputs() { return *inputs_; }
  std::size_t input_index(const std::string& name) const;
  // Appends an input data package (only while streaming).
  void encode_inputs(std::vector<std::uint8_t>& out) const;

  // Output data packages taken, packages refused (malformed, unknown, out of turn) and why the
  // last one was, and the controller's newest text message.
  std::uint64_t data_packages() const { return data_packages_; }
  std::uint64_t refused() const { return refused_; }
  const std::string& last_refusal() const { return last_refusal_; }
  const TextMessage& last_message() const { return last_message_; }
  std::uint64_t messages() const { return messages_; }

 private:
  void fail(const std::string& why);
  void refuse(const std::string& why);
  // Checks a setup reply against the variables asked for; builds the recipe.
  bool take_setup(const RawPackage& pkg, const std::vector<Variable>& asked, const char* what,
                  std::unique_ptr<Recipe>& recipe, std::unique_ptr<RecipeValues>& values);

  double frequency_;
  std::vector<Variable> asked_outputs_, asked_inputs_;
  State state_ = State::kIdle;
  std::string error_;
  ControllerVersion controller_;
  std::unique_ptr<Recipe> output_recipe_, input_recipe_;
  std::unique_ptr<RecipeValues> outputs_, inputs_;
  std::uint64_t data_packages_ = 0, refused_ = 0, messages_ = 0;
  std::string last_refusal_;
  TextMessage last_message_;
};

// A readable name of a client state.
const char* to_string(ClientSession::State state);

}  // namespace wysiwyf::robot::rtde
