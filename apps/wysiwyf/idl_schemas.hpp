#pragma once
// The OMG IDL of a message type as one self-contained text, as MCAP's and Foxglove's "omgidl"
// schema encoding wants it: the IDL files the type's file includes come first, preprocessor
// lines are dropped. Found in the IDL search path (search_paths.hpp: ours, installed or in the
// source tree, and $WYSIWYF_IDL_PATH for users' own).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace wysiwyf::cli {

struct IdlSchema {
  std::string text;
  // Its first member is a std_msgs::Header: the CDR's first 8 bytes after the encapsulation
  // are the sample's stamp (ns on the pipeline's clock).
  bool stamped = false;
};

// nullopt when no IDL file defines `type_name` ("wysiwyf::msg::JointState"); `searched` then
// says where it looked.
std::optional<IdlSchema> idl_schema(const std::string& type_name, std::string& searched);

// The stamp of a sample of a stamped type (IdlSchema::stamped) from its CDR bytes; nullopt where
// the bytes are too short or big-endian (the pipeline writes little-endian).
std::optional<std::int64_t> header_stamp(const std::vector<std::uint8_t>& cdr);

}  // namespace wysiwyf::cli
