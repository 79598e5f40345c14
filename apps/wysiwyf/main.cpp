// wysiwyf: run, validate and inspect pipelines of the WYSIWYF display.
#include <iostream>
#include <stdexcept>

#include "cli.hpp"
#include "wysiwyf/build_info.hpp"

namespace wysiwyf::cli {

std::vector<std::string> Args::values(const std::string& name) {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < args_.size();) {
    if (args_[i] == name) {
      if (i + 1 >= args_.size()) throw UsageError("option " + name + " needs a value");
      out.push_back(args_[i + 1]);
      args_.erase(args_.begin() + i, args_.begin() + i + 2);
    } else if (args_[i].rfind(name + "=", 0) == 0) {
      out.push_back(args_[i].substr(name.size() + 1));
      args_.erase(args_.begin() + i);
    } else {
      ++i;
    }
  }
  return out;
}

std::optional<std::string> Args::value(const std::string& name) {
  auto all = values(name);
  if (all.size() > 1) throw UsageError("option " + name + " given more than once");
  if (all.empty()) return std::nullopt;
  return all.front();
}

bool Args::flag(const std::string& name) {
  bool found = false;
  for (std::size_t i = 0; i < args_.size();) {
    if (args_[i] == name) {
      found = true;
      args_.erase(args_.begin() + i);
    } else {
      ++i;
    }
  }
  return found;
}

std::optional<std::string> Args::take_front() {
  if (args_.empty() || args_.front().rfind("--", 0) == 0) return std::nullopt;
  std::string first = args_.front();
  args_.erase(args_.begin());
  return first;
}

std::vector<std::string> Args::positional() const {
  std::vector<std::string> out;
  for (const auto& a : args_)
    if (a.rfind("--", 0) != 0) out.push_back(a);
  return out;
}

std::vector<std::string> Args::unknown_options() const {
  std::vector<std::string> out;
  for (const auto& a : args_)
    if (a.rfind("--", 0) == 0) out.push_back(a);
  return out;
}

}  // namespace wysiwyf::cli

static const char* kUsage = R"(usage: wysiwyf <command> [options]

  run FILE [--process NAME] [--set PATH=VALUE]... [--progress|--no-progress] [--start-after SECONDS]
        Run a pipeline (or one process group of it) until its duration ends, a component
        stops it, or Ctrl-C. PATH is e.g. tracker.params.threshold or clock.duration.
        --start-after: wait this long with DDS up before t = 0 (a recorder misses nothing).
  validate FILE [--process NAME] [--set PATH=VALUE]...
        Check a pipeline against the component libraries without running it.
  components list
  components describe TYPE
        The component types found on the search path; a type's parameters and ports.
  topic list [--domain N | --pipeline FILE] [--transport T] [--wait SECONDS]
  topic echo TOPIC [--domain N | --pipeline FILE] [--transport T] [--count N] [--timeout SECONDS]
        (--timeout: how long to wait for the first sample, default 10; echo ends after --count
        samples, on Ctrl-C, or when the topic's last writer leaves)
  topic hz TOPIC [--domain N | --pipeline FILE] [--transport T] [--window SECONDS] [--duration SECONDS]
        Inspect the topics of running pipelines on a DDS domain. echo prints any type this build
        or a message library (wysiwyf_add_messages, in lib/wysiwyf/messages) describes.
  record [TOPIC...] [--all] -o FILE.mcap [--domain N | --pipeline FILE] [--transport T] [--duration SECONDS]
        Record topics (or every topic) of a running pipeline into an MCAP file: each sample as
        DDS carried it (CDR), each type's IDL as its schema (omgidl), chunks at least every
        half second (a killed recorder leaves a file readable up to its last chunk).
  play FILE.mcap --into PIPELINE [--set PATH=VALUE]... [--topics A,B] [--rate R] [--loop] [--start-after S]
        Run PIPELINE on the sim clock with the recorded samples delivered to its readers in the
        step of their stamps (a recorded run replays bit for bit; --rate is the pace, 0 flat out).
  play FILE.mcap [--domain N | --pipeline FILE] [--transport T] [--topics A,B] [--rate R] [--loop]
        Publish the recorded samples onto a DDS domain on the real clock, spaced as recorded.
  new component NAME [--dir DIR]
        Write an out-of-tree component folder (source, CMakeLists.txt with find_package(wysiwyf),
        a Harness test) that builds and passes as written.

Components are searched in $WYSIWYF_COMPONENT_PATH, then lib/wysiwyf beside or above the program,
then lib/wysiwyf beside libwysiwyf_core.so; configuration files (scenes, robots, included
pipelines) in $WYSIWYF_CONFIG_PATH, then the prefix's share/wysiwyf/config.
Exit status: 0 success, 1 the run failed (a component threw, faulted or held: the table's state
column says which and why), 2 a usage or configuration error.
)";

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "help" || args[0] == "--help" || args[0] == "-h") {
    std::cout << kUsage;
    return args.empty() ? 2 : 0;
  }
  if (args[0] == "--version") {
    std::cout << "wysiwyf " << WYSIWYF_VERSION << " (kernel build " << WYSIWYF_BUILD_ID << ")\n";
    return 0;
  }
  const std::string command = args[0];
  wysiwyf::cli::Args rest(std::vector<std::string>(args.begin() + 1, args.end()));
  try {
    if (command == "run") return wysiwyf::cli::cmd_run(std::move(rest));
    if (command == "validate") return wysiwyf::cli::cmd_validate(std::move(rest));
    if (command == "components") return wysiwyf::cli::cmd_components(std::move(rest));
    if (command == "topic") return wysiwyf::cli::cmd_topic(std::move(rest));
    if (command == "new") return wysiwyf::cli::cmd_new(std::move(rest));
    if (command == "record") return wysiwyf::cli::cmd_record(std::move(rest));
    if (command == "play") return wysiwyf::cli::cmd_play(std::move(rest));
    std::cerr << "wysiwyf: unknown command '" << command << "'; expected run, validate, components, topic or new\n\n"
              << kUsage;
    return 2;
  } catch (const wysiwyf::cli::UsageError& e) {
    std::cerr << "wysiwyf " << command << ": " << e.what() << "\n(see wysiwyf --help)\n";
    return 2;
  }
}
