// The ports a process's DDS endpoint stands for, as its user data: "wysiwyf-ports W R".
#include <charconv>
#include <string>
#include <string_view>

#include "wysiwyf/dds.hpp"

namespace wysiwyf::dds {

namespace {
constexpr std::string_view kPrefix = "wysiwyf-ports ";
}

std::vector<unsigned char> endpoint_ports_user_data(const EndpointPorts& ports) {
  const std::string text = std::string(kPrefix) + std::to_string(ports.writers) + " " + std::to_string(ports.readers);
  return {text.begin(), text.end()};
}

std::optional<EndpointPorts> endpoint_ports_from_user_data(const std::vector<unsigned char>& data) {
  const std::string_view text(reinterpret_cast<const char*>(data.data()), data.size());
  if (text.size() > 64 || text.substr(0, kPrefix.size()) != kPrefix) return std::nullopt;
  const char* p = text.data() + kPrefix.size();
  const char* end = text.data() + text.size();
  EndpointPorts ports;
  auto [after_writers, e1] = std::from_chars(p, end, ports.writers);
  if (e1 != std::errc() || after_writers == end || *after_writers != ' ') return std::nullopt;
  auto [after_readers, e2] = std::from_chars(after_writers + 1, end, ports.readers);
  if (e2 != std::errc() || after_readers != end) return std::nullopt;
  if (ports.writers < 0 || ports.readers < 0 || ports.writers > kMaxAnnouncedPorts ||
      ports.readers > kMaxAnnouncedPorts)
    return std::nullopt;
  return ports;
}

}  // namespace wysiwyf::dds
