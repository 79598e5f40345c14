// wysiwyf: run, validate and inspect pipelines of the WYSIWYF display.
#include <algorithm>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli.hpp"
#include "wysiwyf/build_info.hpp"
#include "wysiwyf/validator.hpp"  // closest_name

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

namespace {

// Each command: a line in `wysiwyf --help`, its usage in `wysiwyf COMMAND --help` (and, for the
// commands that join a running pipeline's domain, the options they share, once).
struct CommandHelp {
  const char* name;
  const char* summary;
  bool joins_domain;
  const char* text;
};

const CommandHelp kCommands[] = {
    {"run", "Run a pipeline, or one process group of it", false,
     R"(  run FILE [--process NAME] [--set PATH=VALUE]... [--progress|--no-progress] [--start-after SECONDS]
        Run a pipeline (or one process group of it) until its duration ends, a component
        stops it, or Ctrl-C. PATH is e.g. tracker.params.threshold or clock.duration.
        --start-after: wait this long with DDS up before t = 0 (a recorder misses nothing).
)"},
    {"validate", "Check a pipeline file: every mistake at once, where it is", false,
     R"(  validate FILE [--process NAME] [--set PATH=VALUE]... [--print-components]
        Check a pipeline against the component libraries without running it
        (--print-components: print its components' names instead, one a line).
)"},
    {"components", "The component types found, and one type's parameters and ports", false, R"(  components list
  components describe TYPE
        The component types found on the search path; a type's parameters and ports.
)"},
    {"topic", "List, print (echo) or time (hz) the topics of running pipelines", true,
     R"(  topic list [--domain N | --pipeline FILE] [--transport T] [--wait SECONDS]
  topic echo TOPIC [--domain N | --pipeline FILE] [--transport T] [--count N] [--timeout SECONDS]
                   [--field PATH]
        (--timeout: how long to wait for the first sample, default 10; echo ends after --count
        samples, on Ctrl-C, or when the topic's last writer leaves; --field header.stamp,
        position.0: that field of each sample only)
  topic hz TOPIC [--domain N | --pipeline FILE] [--transport T] [--window SECONDS] [--duration SECONDS]
        Inspect the topics of running pipelines on a DDS domain. echo prints any type this build
        or a message library (wysiwyf_add_messages, in lib/wysiwyf/messages) describes. hz gives
        the wall-clock rate and, for stamped types, the rate on the pipeline's own clock.
)"},
    {"monitor", "The component table of every process on a domain, live", true,
     R"(  monitor [--domain N | --pipeline FILE] [--transport T] [--interval SECONDS] [--duration SECONDS] [--once]
        The component table of every process on the domain (state, achieved rate, tick p50/p99,
        overruns, dropped and rejected samples, warnings, the last problem) and the display mode,
        redrawn in place every --interval (0.5 s). --once prints one table and exits.
)"},
    {"bridge", "Serve a domain to Foxglove and to the web dashboard", true,
     R"(  bridge [TOPIC...] [--domain N | --pipeline FILE] [--transport T] [--port P] [--address A]
         [--video TOPIC] [--plot TOPIC:FIELD]... [--duration SECONDS] [--web-root DIR]
        Serve the domain to Foxglove (WebSocket protocol v1 at ws://A:P, default 127.0.0.1:8765:
        every topic advertised with its OMG IDL, samples as CDR, images included) and the web
        dashboard at http://A:P/ (component table, display mode, live plots, the --video topic,
        default display/view). A topic is read only while someone subscribes to it.
        --address 0.0.0.0 serves other machines too (anyone who can reach the port can watch).
)"},
    {"record", "Record topics of a running pipeline into an MCAP file", true,
     R"(  record [TOPIC...] [--all] -o FILE.mcap [--domain N | --pipeline FILE] [--transport T] [--duration SECONDS]
         [--compression zstd|lz4|none] [--images lossless|video|raw]
        Record topics (or every topic) of a running pipeline into an MCAP file: each sample as
        DDS carried it (CDR), each type's IDL as its schema (omgidl), chunks at least every
        half second (a killed recorder leaves a file readable up to its last chunk).
        --compression: of each chunk, lossless; zstd (default, level 1: the smallest files that
        keep up with the demo's images), lz4 (faster, larger), none. play reads all three.
        --images: Image topics; lossless (default): as Foxglove CompressedImage where that is
        smaller than the chunks make them (camera images as lossless WebP, float depth as PNG),
        decoded by play bit for bit; video: as Foxglove CompressedVideo (H.264, lossy, a
        twentieth of the size); raw: as DDS carried them.
)"},
    {"play", "Replay an MCAP file into a pipeline (bit for bit) or onto a domain", true,
     R"(  play FILE.mcap --into PIPELINE [--set PATH=VALUE]... [--topics A,B] [--rate R] [--loop] [--start-after S]
        Run PIPELINE on the sim clock with the recorded samples delivered to its readers in the
        step of their stamps (a recorded run replays bit for bit; --rate is the pace, 0 flat out).
  play FILE.mcap [--domain N | --pipeline FILE] [--transport T] [--topics A,B] [--rate R] [--loop]
        Publish the recorded samples onto a DDS domain on the real clock, spaced as recorded.
)"},
    {"discovery-server", "A Fast DDS Discovery Server, for networks without multicast", false,
     R"(  discovery-server [--listen IPV4:PORT] [--id N] [--domain N]
        A Fast DDS Discovery Server (default 0.0.0.0:11811, id 0), for networks without multicast:
        pipelines name it (dds: {discovery_server: 10.0.0.5:11811}; a list for servers 0, 1, ...),
        the tools take --discovery-server 10.0.0.5:11811. Runs until Ctrl-C.
)"},
    {"new", "Write an out-of-tree component folder that builds and passes its test", false,
     R"(  new component NAME [--dir DIR]
        Write an out-of-tree component folder (source, CMakeLists.txt with find_package(wysiwyf),
        a Harness test) that builds and passes as written.
)"},
    {"calibrate", "Calibrate the wrist sensor, a camera, the camera to the robot; each file checked", false,
     R"(  calibrate wrist-poses --home Q [--count N] [--urdf U] [--sensor-frame F] [--out FILE]
  calibrate wrist --readings FILE [--scene SCENE --out FILE] [--urdf U] [--sensor-frame F]
  calibrate board --out FILE.png [--pixels-per-square N]
  calibrate intrinsics --images DIR --out FILE.yaml
  calibrate stereo --left FILE.yaml --right FILE.yaml --left-images DIR --right-images DIR
                   --out-left FILE.yaml --out-right FILE.yaml [--max-epipolar PX]
  calibrate camera-base-poses --camera FILE.yaml --home Q --out VIEWS.yaml [--count N] [--seed S] [--urdf U]
  calibrate camera-base --camera FILE.yaml --views VIEWS.yaml --out FILE.yaml [--urdf U]
  calibrate lamps --camera FILE.yaml --views VIEWS.yaml --out ARM.urdf [--urdf U] [--gate PX] [--threshold L]
        Each step prints its residual report (every pose's or view's error) and writes its file
        only when the result passes the limits: wrist: the scene with the device's tool_mass and
        tool_com (and the sensor's bias in the report); intrinsics: camera_matrix and
        distortion_coefficients; stereo: each camera's file with rectification_matrix and
        projection_matrix (images of one board position: the same name in both folders);
        camera-base: the same file with base_T_eye (camera_fixed); lamps: a copy of the URDF with
        the marker_* links where the plate's lamps were seen (marker_tracker, camera_sim).
        Q: the arm's joints, comma-separated (rad). Board: --squares-x 10 --squares-y 7
        --square 0.028 --marker 0.021 (m; an A4 sheet). Exit 1 when refused, with the reason.
        The procedure for a lab: docs/calibration.md.
)"},
};

const char* kDomainOptions = R"(
  Joining a running pipeline's domain (--domain N, or --pipeline FILE for its domain, transport,
  keys and discovery servers; --transport default|local|shm|udp|loopback):
        A pipeline on the real clock sends to a tool in batches, every 5 ms, so that watching does
        not slow its loops; --prompt: each sample as it is written (arrival times as sent).
        Secured domain: --identity NAME [--keys DIR] (default: the --pipeline's keys, monitor).
        Without multicast: --discovery-server IPV4:PORT[,...] (default: the --pipeline's).
)";

const char* kFooter = R"(
Components are searched in $WYSIWYF_COMPONENT_PATH, then lib/wysiwyf beside or above the program;
configuration files (scenes, robots, pipelines) in $WYSIWYF_CONFIG_PATH, then share/wysiwyf/config.
Exit status: 0 success, 1 the run failed (the table's state column says why), 2 a usage or
configuration error. Every command in full: share/doc/wysiwyf/command-line.md (docs/ in the source).
)";

void print_usage(std::ostream& out) {
  out << "usage: wysiwyf <command> [options]     (wysiwyf <command> --help: its options)\n\n";
  for (const auto& c : kCommands) {
    const std::string name = c.name;
    out << "  " << name << std::string(name.size() < 18 ? 18 - name.size() : 1, ' ') << c.summary << "\n";
  }
  out << kFooter;
}

void print_command_usage(const CommandHelp& c) {
  std::cout << "usage:\n" << c.text << (c.joins_domain ? kDomainOptions : "");
}

const CommandHelp* find_command(const std::string& name) {
  for (const auto& c : kCommands)
    if (name == c.name) return &c;
  return nullptr;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "help" || args[0] == "--help" || args[0] == "-h") {
    if (args.size() > 1 && args[0] == "help" && find_command(args[1])) {
      print_command_usage(*find_command(args[1]));
      return 0;
    }
    print_usage(args.empty() ? std::cerr : std::cout);
    return args.empty() ? 2 : 0;
  }
  if (args[0] == "--version") {
    std::cout << "wysiwyf " << WYSIWYF_VERSION << " (kernel build " << WYSIWYF_BUILD_ID << ")\n";
    return 0;
  }
  const std::string command = args[0];
  const CommandHelp* help = find_command(command);
  if (help && std::find_if(args.begin() + 1, args.end(),
                           [](const std::string& a) { return a == "--help" || a == "-h"; }) != args.end()) {
    print_command_usage(*help);
    return 0;
  }
  wysiwyf::cli::Args rest(std::vector<std::string>(args.begin() + 1, args.end()));
  try {
    if (command == "run") return wysiwyf::cli::cmd_run(std::move(rest));
    if (command == "validate") return wysiwyf::cli::cmd_validate(std::move(rest));
    if (command == "components") return wysiwyf::cli::cmd_components(std::move(rest));
    if (command == "topic") return wysiwyf::cli::cmd_topic(std::move(rest));
    if (command == "new") return wysiwyf::cli::cmd_new(std::move(rest));
    if (command == "record") return wysiwyf::cli::cmd_record(std::move(rest));
    if (command == "play") return wysiwyf::cli::cmd_play(std::move(rest));
    if (command == "monitor") return wysiwyf::cli::cmd_monitor(std::move(rest));
    if (command == "bridge") return wysiwyf::cli::cmd_bridge(std::move(rest));
    if (command == "discovery-server") return wysiwyf::cli::cmd_discovery_server(std::move(rest));
    if (command == "calibrate") return wysiwyf::cli::cmd_calibrate(std::move(rest));
    std::vector<std::string> names;
    for (const auto& c : kCommands) names.emplace_back(c.name);
    const std::string near = wysiwyf::closest_name(command, names);
    std::cerr << "wysiwyf: unknown command '" << command << "'"
              << (near.empty() ? std::string("; expected one of:") : "; did you mean '" + near + "'? Expected one of:");
    for (const auto& name : names) std::cerr << " " << name;
    std::cerr << "\n";
    return 2;
  } catch (const wysiwyf::cli::UsageError& e) {
    std::cerr << "wysiwyf " << command << ": " << e.what() << "\n(see wysiwyf " << command << " --help)\n";
    return 2;
  } catch (const std::exception& e) {  // DDS refused (a domain, an identity): said, not a crash
    std::cerr << "wysiwyf " << command << ": " << e.what() << "\n";
    return 1;
  }
}
