#pragma once
// RTDE's packages (protocol version 2) to and from bytes: an encoder per package, which appends
// the whole package (header included) to a byte vector, and a decoder per payload form, which
// returns none for a payload that is not exactly of that form (short, long, or with values the
// guide does not allow). The client (driver) and the server (emulator) use the same code.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "rtde/protocol.hpp"
#include "rtde/recipe.hpp"

namespace wysiwyf::robot::rtde {

// Limits on setup requests, for both ends: variable names are [A-Za-z0-9_], at most this long.
constexpr std::size_t kMaxVariableName = 64;
constexpr std::size_t kMaxRecipeFields = 128;
// The fastest output the e-Series controller streams, Hz.
constexpr double kMaxOutputFrequency = 500.0;

struct ControllerVersion {
  std::uint32_t major = 0, minor = 0, bugfix = 0, build = 0;
};

struct TextMessage {
  std::string message;  // at most 255 bytes on the wire (longer is cut)
  std::string source;   // at most 255 bytes
  MessageLevel level = MessageLevel::kInfo;
};

struct SetupOutputsRequest {
  double frequency = 0;  // Hz, (0, kMaxOutputFrequency]
  std::vector<std::string> names;
};

// The controller's answer to a setup request: the recipe id (0: refused) and, per requested
// name, its type's name, NOT_FOUND or IN_USE.
struct SetupReply {
  std::uint8_t recipe_id = 0;
  std::vector<std::string> types;
};

// ---- encoders: each appends one whole package to `out`
void encode_request_protocol_version(std::vector<std::uint8_t>& out, std::uint16_t version);
void encode_accepted(std::vector<std::uint8_t>& out, PackageType reply_to, bool accepted);  // V, S, P replies
void encode_get_urcontrol_version(std::vector<std::uint8_t>& out);
void encode_urcontrol_version(std::vector<std::uint8_t>& out, const ControllerVersion& v);
void encode_setup_outputs(std::vector<std::uint8_t>& out, const SetupOutputsRequest& request);
void encode_setup_inputs(std::vector<std::uint8_t>& out, const std::vector<std::string>& names);
void encode_setup_reply(std::vector<std::uint8_t>& out, PackageType reply_to, const SetupReply& reply);
void encode_start(std::vector<std::uint8_t>& out);
void encode_pause(std::vector<std::uint8_t>& out);
void encode_text_message(std::vector<std::uint8_t>& out, const TextMessage& message);
void encode_data_package(std::vector<std::uint8_t>& out, const RecipeValues& values);

// ---- decoders of payloads (the bytes after the header)
// RTDE_REQUEST_PROTOCOL_VERSION from the client: the version asked for.
std::optional<std::uint16_t> decode_request_protocol_version(const std::uint8_t* p, std::size_t n);
// The controller's one-byte answer to V, S or P: accepted or not (a byte other than 0 or 1: none).
std::optional<bool> decode_accepted(const std::uint8_t* p, std::size_t n);
// The controller's RTDE_GET_URCONTROL_VERSION answer.
std::optional<ControllerVersion> decode_urcontrol_version(const std::uint8_t* p, std::size_t n);
// A client's output setup: a finite frequency in (0, 500] and 1..128 valid, distinct names.
std::optional<SetupOutputsRequest> decode_setup_outputs(const std::uint8_t* p, std::size_t n);
// A client's input setup: 1..128 valid, distinct names.
std::optional<std::vector<std::string>> decode_setup_inputs(const std::uint8_t* p, std::size_t n);
// The controller's answer to a setup request.
std::optional<SetupReply> decode_setup_reply(const std::uint8_t* p, std::size_t n);
// RTDE_TEXT_MESSAGE (protocol 2 layout).
std::optional<TextMessage> decode_text_message(const std::uint8_t* p, std::size_t n);

// Splits a comma-separated list; none when an item is empty, too long or not [A-Za-z0-9_], or
// there are more than kMaxRecipeFields (or none).
std::optional<std::vector<std::string>> split_names(std::string_view list);

}  // namespace wysiwyf::robot::rtde
