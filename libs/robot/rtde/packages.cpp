#include "rtde/packages.hpp"

#include <cmath>

#include "rtde/wire.hpp"

namespace wysiwyf::robot::rtde {
namespace {

// Appends a header for `type` and returns where its size goes; finish() writes it.
std::size_t begin(std::vector<std::uint8_t>& out, PackageType type) {
  const std::size_t at = out.size();
  WireWriter w(out);
  w.u16(0);
  w.u8(static_cast<std::uint8_t>(type));
  return at;
}

void finish(std::vector<std::uint8_t>& out, std::size_t at) {
  const std::size_t size = out.size() - at;
  out[at] = static_cast<std::uint8_t>(size >> 8);
  out[at + 1] = static_cast<std::uint8_t>(size);
}

std::string join(const std::vector<std::string>& items) {
  std::string s;
  for (const auto& i : items) s += (s.empty() ? "" : ",") + i;
  return s;
}

bool valid_name(std::string_view name) {
  if (name.empty() || name.size() > kMaxVariableName) return false;
  for (char c : name)
    if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_')) return false;
  return true;
}

std::string cut(const std::string& s) { return s.size() > 255 ? s.substr(0, 255) : s; }

// Splits a comma-separated list of names ([A-Za-z0-9_], 1..kMaxRecipeFields of them); with
// `distinct`, a name may not repeat.
std::optional<std::vector<std::string>> split_list(std::string_view list, bool distinct) {
  std::vector<std::string> names;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = list.find(',', start);
    const std::string_view item = list.substr(start, comma == std::string_view::npos ? list.npos : comma - start);
    if (!valid_name(item) || names.size() == kMaxRecipeFields) return std::nullopt;
    if (distinct)
      for (const auto& n : names)
        if (n == item) return std::nullopt;
    names.emplace_back(item);
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return names;
}

}  // namespace

std::optional<std::vector<std::string>> split_names(std::string_view list) { return split_list(list, true); }

void encode_request_protocol_version(std::vector<std::uint8_t>& out, std::uint16_t version) {
  const std::size_t at = begin(out, PackageType::kRequestProtocolVersion);
  WireWriter(out).u16(version);
  finish(out, at);
}

void encode_accepted(std::vector<std::uint8_t>& out, PackageType reply_to, bool accepted) {
  const std::size_t at = begin(out, reply_to);
  WireWriter(out).u8(accepted ? 1 : 0);
  finish(out, at);
}

void encode_get_urcontrol_version(std::vector<std::uint8_t>& out) {
  finish(out, begin(out, PackageType::kGetUrcontrolVersion));
}

void encode_urcontrol_version(std::vector<std::uint8_t>& out, const ControllerVersion& v) {
  const std::size_t at = begin(out, PackageType::kGetUrcontrolVersion);
  WireWriter w(out);
  w.u32(v.major), w.u32(v.minor), w.u32(v.bugfix), w.u32(v.build);
  finish(out, at);
}

void encode_setup_outputs(std::vector<std::uint8_t>& out, const SetupOutputsRequest& request) {
  const std::size_t at = begin(out, PackageType::kSetupOutputs);
  WireWriter w(out);
  w.f64(request.frequency);
  w.text(join(request.names));
  finish(out, at);
}

void encode_setup_inputs(std::vector<std::uint8_t>& out, const std::vector<std::string>& names) {
  const std::size_t at = begin(out, PackageType::kSetupInputs);
  WireWriter(out).text(join(names));
  finish(out, at);
}

void encode_setup_reply(std::vector<std::uint8_t>& out, PackageType reply_to, const SetupReply& reply) {
  const std::size_t at = begin(out, reply_to);
  WireWriter w(out);
  w.u8(reply.recipe_id);
  w.text(join(reply.types));
  finish(out, at);
}

void encode_start(std::vector<std::uint8_t>& out) { finish(out, begin(out, PackageType::kStart)); }
void encode_pause(std::vector<std::uint8_t>& out) { finish(out, begin(out, PackageType::kPause)); }

void encode_text_message(std::vector<std::uint8_t>& out, const TextMessage& message) {
  const std::size_t at = begin(out, PackageType::kTextMessage);
  WireWriter w(out);
  const std::string text = cut(message.message), source = cut(message.source);
  w.u8(static_cast<std::uint8_t>(text.size()));
  w.text(text);
  w.u8(static_cast<std::uint8_t>(source.size()));
  w.text(source);
  w.u8(static_cast<std::uint8_t>(message.level));
  finish(out, at);
}

void encode_data_package(std::vector<std::uint8_t>& out, const RecipeValues& values) {
  const std::size_t at = begin(out, PackageType::kDataPackage);
  out.push_back(values.recipe().id());
  out.insert(out.end(), values.bytes().begin(), values.bytes().end());
  finish(out, at);
}

std::optional<std::uint16_t> decode_request_protocol_version(const std::uint8_t* p, std::size_t n) {
  WireReader r(p, n);
  const std::uint16_t v = r.u16();
  return r.done() ? std::optional<std::uint16_t>(v) : std::nullopt;
}

std::optional<bool> decode_accepted(const std::uint8_t* p, std::size_t n) {
  WireReader r(p, n);
  const std::uint8_t v = r.u8();
  if (!r.done() || v > 1) return std::nullopt;
  return v == 1;
}

std::optional<ControllerVersion> decode_urcontrol_version(const std::uint8_t* p, std::size_t n) {
  WireReader r(p, n);
  ControllerVersion v;
  v.major = r.u32(), v.minor = r.u32(), v.bugfix = r.u32(), v.build = r.u32();
  return r.done() ? std::optional<ControllerVersion>(v) : std::nullopt;
}

std::optional<SetupOutputsRequest> decode_setup_outputs(const std::uint8_t* p, std::size_t n) {
  WireReader r(p, n);
  SetupOutputsRequest request;
  request.frequency = r.f64();
  const std::string_view list = r.rest();
  if (r.failed() || !std::isfinite(request.frequency) || request.frequency <= 0 ||
      request.frequency > kMaxOutputFrequency)
    return std::nullopt;
  auto names = split_names(list);
  if (!names) return std::nullopt;
  request.names = std::move(*names);
  return request;
}

std::optional<std::vector<std::string>> decode_setup_inputs(const std::uint8_t* p, std::size_t n) {
  WireReader r(p, n);
  const std::string_view list = r.rest();
  if (r.failed()) return std::nullopt;
  return split_names(list);
}

std::optional<SetupReply> decode_setup_reply(const std::uint8_t* p, std::size_t n) {
  WireReader r(p, n);
  SetupReply reply;
  reply.recipe_id = r.u8();
  const std::string_view list = r.rest();
  if (r.failed()) return std::nullopt;
  // NOT_FOUND and IN_USE may repeat; every item is still a name of [A-Z0-9_].
  auto types = split_list(list, false);
  if (!types) return std::nullopt;
  reply.types = std::move(*types);
  return reply;
}

std::optional<TextMessage> decode_text_message(const std::uint8_t* p, std::size_t n) {
  WireReader r(p, n);
  TextMessage m;
  m.message = std::string(r.text(r.u8()));
  m.source = std::string(r.text(r.u8()));
  const std::uint8_t level = r.u8();
  if (!r.done() || level > static_cast<std::uint8_t>(MessageLevel::kInfo)) return std::nullopt;
  m.level = static_cast<MessageLevel>(level);
  return m;
}

}  // namespace wysiwyf::robot::rtde
