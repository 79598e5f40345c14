#pragma once
// The controller's end of one RTDE connection, as the UR controller behaves to a client: it
// answers the protocol version (2 only), the controller version, output and input setups (each
// variable's type, NOT_FOUND, or IN_USE when another connection's input recipe holds it), start
// and pause, and takes the client's input data packages. What it cannot take (an unknown package,
// a malformed payload, a setup while streaming, data of an unknown recipe) is refused, counted
// and answered with an error text message; the connection stays up. Sockets are the caller's.
#include <cstdint>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "rtde/framer.hpp"
#include "rtde/packages.hpp"
#include "rtde/recipe.hpp"

namespace wysiwyf::robot::rtde {

// Which connection's input recipe holds each input variable (the controller allows one writer).
class InputOwners {
 public:
  // Claims every name for `owner`; false (nothing claimed) when another owner holds one.
  bool claim(const void* owner, const std::vector<std::string>& names);
  // Frees every name `owner` holds.
  void release(const void* owner);
  // Whether another owner than `owner` holds `name`.
  bool held_by_other(const void* owner, const std::string& name) const;

 private:
  std::map<std::string, const void*> owner_;
};

class ServerSession {
 public:
  // `owners` is shared by the controller's connections and must outlive the session.
  ServerSession(ControllerVersion version, InputOwners& owners);
  ~ServerSession();
  ServerSession(const ServerSession&) = delete;
  ServerSession& operator=(const ServerSession&) = delete;

  // Handles one package from the client, appending the replies to `out`.
  void handle(const RawPackage& pkg, std::vector<std::uint8_t>& out);

  // Whether the client has started the stream (and not paused it).
  bool streaming() const { return streaming_; }
  // The output recipe and its frequency (null before a setup).
  const Recipe* output_recipe() const { return output_recipe_.get(); }
  double output_frequency() const { return output_frequency_; }
  // The values the next data package carries: the caller fills them, then encode_outputs().
  RecipeValues* outputs() { return outputs_.get(); }
  // Appends a data package of the output recipe to `out`.
  void encode_outputs(std::vector<std::uint8_t>& out) const;

  // The newest values of input recipe `id` (null for no such recipe), and how many input data
  // packages have arrived in all.
  const RecipeValues* inputs(std::uint8_t id) const;
  std::uint64_t input_packages() const { return input_packages_; }
  // Packages refused, and why the last one was.
  std::uint64_t refused() const { return refused_; }
  const std::string& last_refusal() const { return last_refusal_; }

 private:
  void refuse(const std::string& why, std::vector<std::uint8_t>& out);
  void setup_outputs(const RawPackage& pkg, std::vector<std::uint8_t>& out);
  void setup_inputs(const RawPackage& pkg, std::vector<std::uint8_t>& out);
  void data(const RawPackage& pkg, std::vector<std::uint8_t>& out);

  ControllerVersion version_;
  InputOwners& owners_;
  bool version_agreed_ = false;
  bool streaming_ = false;
  std::unique_ptr<Recipe> output_recipe_;
  std::unique_ptr<RecipeValues> outputs_;
  double output_frequency_ = 0;
  struct Input {
    std::unique_ptr<Recipe> recipe;
    std::unique_ptr<RecipeValues> values;
  };
  std::vector<Input> inputs_;
  std::uint8_t next_id_ = 1;
  std::uint64_t input_packages_ = 0, refused_ = 0;
  std::string last_refusal_;
};

}  // namespace wysiwyf::robot::rtde
