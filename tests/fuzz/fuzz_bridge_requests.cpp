// libFuzzer target: the bridge's readers of what a network client sends (scripts/fuzz): one text
// frame as a Foxglove and as a dashboard request, and the same bytes as an HTTP request target.
// Nothing may crash, throw or hang; a request is either read or refused with a problem; a target
// resolves only to a regular file inside the web root.
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string_view>

#include "bridge/client_requests.hpp"
#include "bridge/web_files.hpp"

namespace {

namespace fs = std::filesystem;

// A small web root beside a file that must never be served.
const fs::path& web_root() {
  static const fs::path root = [] {
    const fs::path base = fs::temp_directory_path() / ("wysiwyf_fuzz_bridge_" + std::to_string(::getpid()));
    fs::create_directories(base / "root" / "vendor");
    std::ofstream(base / "root" / "index.html") << "index";
    std::ofstream(base / "root" / "vendor" / "a.js") << "a";
    std::ofstream(base / "secret") << "secret";
    std::error_code ec;
    fs::create_symlink(base / "secret", base / "root" / "link", ec);
    return fs::canonical(base / "root");
  }();
  return root;
}

bool inside(const fs::path& root, const fs::path& path) {
  const auto r = root.native(), p = path.native();
  return p.size() > r.size() && p.compare(0, r.size(), r) == 0 && p[r.size()] == '/';
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace wysiwyf::bridge;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const FoxgloveRequest f = parse_foxglove_request(text);
  if ((f.op == FoxgloveRequest::Op::kInvalid || f.op == FoxgloveRequest::Op::kUnsupported) == f.problem.empty())
    std::abort();
  if (f.subscriptions.size() > kMaxSubscriptionsPerRequest || f.unsubscribe.size() > kMaxSubscriptionsPerRequest)
    std::abort();
  const DashboardRequest d = parse_dashboard_request(text);
  if ((d.op == DashboardRequest::Op::kInvalid) == d.problem.empty()) std::abort();
  if (d.op != DashboardRequest::Op::kInvalid &&
      (d.topic.empty() || d.topic.size() > kMaxNameBytes || d.field.empty() || d.field.size() > kMaxNameBytes))
    std::abort();
  std::string problem;
  if (const auto file = resolve_web_file(web_root(), text, problem)) {
    if (!inside(web_root(), file->path) || !fs::is_regular_file(file->path)) std::abort();
    if (file->path.filename() == "secret") std::abort();
  } else if (problem.empty()) {
    std::abort();
  }
  return 0;
}
