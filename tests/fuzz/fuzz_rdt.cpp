// libFuzzer target: the RDT record and request parsers on arbitrary datagrams (scripts/fuzz).
// A parse either succeeds or returns an error; it never reads out of bounds or crashes, and what
// it accepts encodes back to the same bytes.
#include <cstdlib>
#include <cstring>

#include "netft_rdt/rdt_protocol.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace wysiwyf::robot::rdt;
  const RecordResult r = parse_record(data, size, 1'000'000);
  if (r.error == ParseError::kNone) {
    const auto again = encode(r.record);
    if (size != again.size() || std::memcmp(data, again.data(), size) != 0) std::abort();
  }
  const RequestResult q = parse_request(data, size);
  if (q.error == ParseError::kNone) {
    const auto again = encode(q.request);
    if (size != again.size() || std::memcmp(data, again.data(), size) != 0) std::abort();
  }
  (void)to_string(r.error);
  return 0;
}
