#include "web_files.hpp"

#include <algorithm>
#include <fstream>
#include <vector>

namespace wysiwyf::bridge {

namespace fs = std::filesystem;

namespace {

bool segment_ok(std::string_view s) {
  if (s.empty() || s.front() == '.') return false;
  return std::all_of(s.begin(), s.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-' ||
           c == '.';
  });
}

// Whether `path` lies inside `root` (both canonical).
bool inside(const fs::path& root, const fs::path& path) {
  auto r = root.begin(), p = path.begin();
  for (; r != root.end(); ++r, ++p)
    if (p == path.end() || *p != *r) return false;
  return p != path.end();
}

}  // namespace

std::optional<WebFile> resolve_web_file(const fs::path& web_root, std::string_view target, std::string& problem) {
  if (web_root.empty()) {
    problem = "this bridge serves no dashboard (its files were not found)";
    return std::nullopt;
  }
  if (target.size() > kMaxTargetBytes) {
    problem = "a target of " + std::to_string(target.size()) + " bytes";
    return std::nullopt;
  }
  target = target.substr(0, target.find_first_of("?#"));
  if (target.empty() || target.front() != '/') {
    problem = "not an origin-form target (expected it to start with '/')";
    return std::nullopt;
  }
  if (target == "/") target = "/index.html";
  fs::path relative;
  for (std::size_t begin = 1; begin <= target.size();) {
    const std::size_t end = std::min(target.find('/', begin), target.size());
    const std::string_view segment = target.substr(begin, end - begin);
    if (!segment_ok(segment)) {
      problem =
          "a path segment that is empty, hidden, '..' or has characters other than letters, digits, '_', '-', '.'";
      return std::nullopt;
    }
    relative /= std::string(segment);
    begin = end + 1;
  }
  std::error_code ec;
  const fs::path root = fs::canonical(web_root, ec);
  if (ec) {
    problem = "the web root " + web_root.string() + " cannot be resolved: " + ec.message();
    return std::nullopt;
  }
  const fs::path file = fs::canonical(root / relative, ec);
  if (ec) {
    problem = "no such file";
    return std::nullopt;
  }
  if (!inside(root, file)) {
    problem = "it resolves outside the web root (a symbolic link?)";
    return std::nullopt;
  }
  const auto status = fs::status(file, ec);
  if (ec || !fs::is_regular_file(status)) {
    problem = "not a regular file";
    return std::nullopt;
  }
  const auto size = fs::file_size(file, ec);
  if (ec || size > kMaxWebFileBytes) {
    problem = "larger than " + std::to_string(kMaxWebFileBytes) + " bytes";
    return std::nullopt;
  }
  return WebFile{file, size};
}

std::optional<std::string> read_web_file(const WebFile& file, std::uintmax_t max_bytes) {
  std::ifstream in(file.path, std::ios::binary);
  if (!in) return std::nullopt;
  std::string bytes(static_cast<std::size_t>(std::min(file.size, max_bytes)), '\0');
  in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  bytes.resize(static_cast<std::size_t>(in.gcount()));
  return bytes;
}

const char* web_content_type(const fs::path& file) {
  const auto ext = file.extension().string();
  if (ext == ".html") return "text/html; charset=utf-8";
  if (ext == ".js" || ext == ".mjs") return "text/javascript; charset=utf-8";
  if (ext == ".css") return "text/css; charset=utf-8";
  if (ext == ".json") return "application/json";
  if (ext == ".png") return "image/png";
  if (ext == ".svg") return "image/svg+xml";
  return "application/octet-stream";
}

}  // namespace wysiwyf::bridge
