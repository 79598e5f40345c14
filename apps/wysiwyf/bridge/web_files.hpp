#pragma once
// The bridge's HTTP side serves the dashboard's files and nothing else: a request target is
// mapped to a regular file inside the web root only after every check below, so no path (an
// absolute one, `..`, an encoded byte, a symbolic link out of the root, a device) reaches
// anything outside it, and no file is read without bound.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace wysiwyf::bridge {

constexpr std::size_t kMaxTargetBytes = 1024;
constexpr std::uintmax_t kMaxWebFileBytes = 16u << 20;

struct WebFile {
  std::filesystem::path path;  // canonical, inside the canonical web root
  std::uintmax_t size = 0;
};

// The file that `target` (an HTTP request target: "/", "/dashboard.js?v=2") names under
// `web_root`, or nullopt with `problem` saying why (for the log, not the client). Only path
// segments of letters, digits, '_', '-' and '.' are accepted, none empty, none starting with a
// dot; "/" is index.html.
std::optional<WebFile> resolve_web_file(const std::filesystem::path& web_root, std::string_view target,
                                        std::string& problem);

// The file's bytes, at most `max_bytes` of them (a file that grew since it was resolved is cut).
std::optional<std::string> read_web_file(const WebFile& file, std::uintmax_t max_bytes = kMaxWebFileBytes);

// The Content-Type for a file of the dashboard, by its extension.
const char* web_content_type(const std::filesystem::path& file);

}  // namespace wysiwyf::bridge
