// libFuzzer target: RTDE bytes from a peer (scripts/fuzz rtde). The first byte chunks the rest
// into feeds of the framer; every whole package is decoded by every decoder of its type and read
// as a data package of a fixed recipe, and both ends of a connection (the controller's session
// and the driver's, mid-handshake) take it. Nothing may read out of bounds or crash, and what a
// decoder accepts encodes back to the same bytes.
#include <cstdlib>
#include <cstring>

#include "rtde/client_session.hpp"
#include "rtde/framer.hpp"
#include "rtde/packages.hpp"
#include "rtde/server_session.hpp"
#include "rtde/variables.hpp"

namespace {

using namespace wysiwyf::robot::rtde;

// The package `encode` writes must equal the header and payload that were read.
template <typename Encode>
void same_back(const RawPackage& pkg, Encode encode) {
  std::vector<std::uint8_t> out;
  encode(out);
  if (out.size() != kHeaderSize + pkg.size || out[2] != pkg.type ||
      std::memcmp(out.data() + kHeaderSize, pkg.payload, pkg.size) != 0)
    std::abort();
}

void decode_all(const RawPackage& pkg, RecipeValues& values) {
  const auto type = static_cast<PackageType>(pkg.type);
  if (auto v = decode_request_protocol_version(pkg.payload, pkg.size);
      v && type == PackageType::kRequestProtocolVersion)
    same_back(pkg, [&](auto& out) { encode_request_protocol_version(out, *v); });
  if (auto a = decode_accepted(pkg.payload, pkg.size); a && package_type(pkg.type))
    same_back(pkg, [&](auto& out) { encode_accepted(out, type, *a); });
  if (auto v = decode_urcontrol_version(pkg.payload, pkg.size); v && type == PackageType::kGetUrcontrolVersion)
    same_back(pkg, [&](auto& out) { encode_urcontrol_version(out, *v); });
  if (auto r = decode_setup_outputs(pkg.payload, pkg.size); r && type == PackageType::kSetupOutputs)
    same_back(pkg, [&](auto& out) { encode_setup_outputs(out, *r); });
  if (auto n = decode_setup_inputs(pkg.payload, pkg.size); n && type == PackageType::kSetupInputs) {
    same_back(pkg, [&](auto& out) { encode_setup_inputs(out, *n); });
    for (const auto& name : *n) (void)input_type(name), (void)output_type(name);
  }
  if (auto r = decode_setup_reply(pkg.payload, pkg.size); r && package_type(pkg.type)) {
    same_back(pkg, [&](auto& out) { encode_setup_reply(out, type, *r); });
    for (const auto& t : r->types) (void)field_type(t);
  }
  if (auto m = decode_text_message(pkg.payload, pkg.size); m && type == PackageType::kTextMessage)
    same_back(pkg, [&](auto& out) { encode_text_message(out, *m); });
  if (values.read(pkg.payload, pkg.size) && type == PackageType::kDataPackage)
    same_back(pkg, [&](auto& out) { encode_data_package(out, values); });
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  static const Recipe recipe(
      1, {"timestamp", "actual_q", "robot_mode", "output_bit_register_64", "runtime_state"},
      {FieldType::kDouble, FieldType::kVector6d, FieldType::kInt32, FieldType::kBool, FieldType::kUint32});
  RecipeValues values(recipe);
  InputOwners owners;
  ServerSession server({5, 11, 3, 0}, owners);
  ClientSession client(500, {{"timestamp", FieldType::kDouble}, {"actual_q", FieldType::kVector6d}},
                       {{"input_int_register_24", FieldType::kInt32}});
  std::vector<std::uint8_t> replies;
  client.begin(replies);
  PackageFramer framer;
  const std::size_t chunk = 1 + data[0] % 64;
  for (std::size_t at = 1; at < size; at += chunk) {
    framer.feed(data + at, std::min(chunk, size - at));
    while (const auto pkg = framer.next()) {
      decode_all(*pkg, values);
      replies.clear();
      server.handle(*pkg, replies);
      client.handle(*pkg, replies);
      if (server.streaming()) server.encode_outputs(replies);
      client.encode_inputs(replies);
    }
  }
  (void)framer.error();
  return 0;
}
