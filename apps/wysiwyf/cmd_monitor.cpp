// wysiwyf monitor: the component table of the running pipelines on a domain (the kernel's
// wysiwyf/diagnostics from every process) and the display mode, redrawn in place in a terminal.
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <functional>
#include <limits>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <iostream>
#include <map>
#include <mutex>
#include <sstream>
#include <thread>

#include "bridge/sample_json.hpp"
#include "dds_session.hpp"
#include "raw_cdr_type.hpp"
#include "wysiwyf/runtime.hpp"

namespace wysiwyf::cli {

using namespace eprosima::fastdds::dds;
using json = nlohmann::json;

namespace {

// Keeps the last sample of each diagnostics instance and of the display mode, decoded.
class Latest final : public DataReaderListener {
 public:
  Latest(std::string type, bool keyed_by_instance) : type_(std::move(type)), keyed_(keyed_by_instance) {}
  void on_data_available(DataReader* reader) override {
    SampleInfo si;
    while (reader->take_next_sample(&sample_, &si) == ReturnCode_t::RETCODE_OK) {
      if (!si.valid_data) continue;
      std::lock_guard<std::mutex> lock(mutex_);
      auto j = decoder_.to_json(type_, sample_.bytes);
      if (!j) continue;
      const std::string key = keyed_ ? j->value("instance", "") : "";
      samples_[key] = {std::move(*j), Clock::now()};
    }
  }
  std::map<std::string, std::pair<json, Clock::time_point>> samples() {
    std::lock_guard<std::mutex> lock(mutex_);
    return samples_;
  }

 private:
  std::string type_;
  bool keyed_;
  std::mutex mutex_;
  RawCdr sample_;
  bridge::SampleDecoder decoder_;
  std::map<std::string, std::pair<json, Clock::time_point>> samples_;
};

std::string num(const json& j, const char* key, int precision) {
  if (!j.contains(key) || !j[key].is_number()) return "-";
  std::ostringstream out;
  out << std::fixed << std::setprecision(precision) << j[key].get<double>();
  return out.str();
}

std::string fit(std::string s, std::size_t width) {
  if (s.size() > width) s = s.substr(0, width > 1 ? width - 1 : 0) + "~";
  return s;
}

// "dropped at image: 3, pose: 1" from a row's dropped_by_port ("" when none dropped).
std::string dropped_by_port(const json& row) {
  if (!row.contains("dropped_by_port") || !row["dropped_by_port"].is_array() || row["dropped_by_port"].empty())
    return "";
  std::string out = "dropped at ";
  for (const auto& p : row["dropped_by_port"])
    out += (out.size() > 11 ? ", " : "") + p.value("port", "?") + ": " + p.value("count", json(0)).dump();
  return out;
}

// An enumerator as a word: STATE_ACTIVE -> active, MODE_SURFACE -> surface.
std::string label(const std::string& enumerator) {
  std::string out = enumerator.substr(enumerator.find('_') == std::string::npos ? 0 : enumerator.find('_') + 1);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

// The terminal's size (columns, rows); 160 x 1000 when not a terminal (a pipe, a file: no limit).
std::pair<int, int> terminal_size() {
  winsize w{};
  if (isatty(STDOUT_FILENO) && ioctl(STDOUT_FILENO, TIOCGWINSZ, &w) == 0 && w.ws_col > 0)
    return {std::max<int>(w.ws_col, 40), std::max<int>(w.ws_row, 4)};
  return {160, 1000};
}

// One column of the table: its heading, width (with the space before it), side, and the text of
// a row. `keep`: the narrower the terminal, the fewer columns kept, lowest keep dropped first.
struct Column {
  const char* heading;
  int width;
  bool left;
  int keep;
  std::function<std::string(const json&, const std::string& state)> text;
};

const std::vector<Column>& columns() {
  static const std::vector<Column> all{
      {"component", 16, true, 100, [](const json& j, const std::string&) { return fit(j.value("instance", ""), 15); }},
      {"type", 18, true, 10, [](const json& j, const std::string&) { return fit(j.value("type", ""), 17); }},
      {"process", 10, true, 50, [](const json& j, const std::string&) { return fit(j.value("process", ""), 9); }},
      {"state", 9, true, 90, [](const json&, const std::string& state) { return fit(state, 8); }},
      {"rate Hz", 15, false, 80,
       [](const json& j, const std::string&) { return num(j, "tick_rate_hz", 1) + "/" + num(j, "rate_hz", 0); }},
      {"p50 us", 9, false, 20, [](const json& j, const std::string&) { return num(j, "tick_time_p50_us", 1); }},
      {"p99 us", 9, false, 70, [](const json& j, const std::string&) { return num(j, "tick_time_p99_us", 1); }},
      {"overrun", 9, false, 60, [](const json& j, const std::string&) { return num(j, "overruns", 0); }},
      {"dropped", 9, false, 40, [](const json& j, const std::string&) { return num(j, "dropped_samples", 0); }},
      {"rejected", 9, false, 30, [](const json& j, const std::string&) { return num(j, "rejected_samples", 0); }},
      {"warn", 7, false, 45, [](const json& j, const std::string&) { return num(j, "warnings", 0); }},
  };
  return all;
}

// The columns that fit `width` with room for the problem column (at least kMinProblem), in order.
constexpr int kMinProblem = 10;
std::vector<const Column*> columns_for(int width) {
  std::vector<const Column*> kept;
  int total = 2 + kMinProblem;  // ("  problem")
  for (const auto& c : columns()) {
    kept.push_back(&c);
    total += c.width;
  }
  while (total > width && kept.size() > 1) {
    auto lowest =
        std::min_element(kept.begin(), kept.end(), [](const Column* a, const Column* b) { return a->keep < b->keep; });
    total -= (*lowest)->width;
    kept.erase(lowest);
  }
  return kept;
}

// The table, one row per component, ordered by process group then name, fitted to the terminal:
// no line longer than its width (columns dropped, the problem cut), no more lines than its rows.
std::string render(int domain, const std::map<std::string, std::pair<json, Clock::time_point>>& rows,
                   const std::map<std::string, std::pair<json, Clock::time_point>>& mode, std::pair<int, int> size) {
  const auto [width, height] = size;
  std::ostringstream out;
  std::ostringstream title;
  title << "wysiwyf monitor  domain " << domain << "  ";
  if (auto it = mode.find(""); it != mode.end()) {
    const auto& m = it->second.first;
    title << "display mode: " << label(m.value("mode", "?"));
    if (!m.value("reason", "").empty()) title << " (" << m.value("reason", "") << ")";
  } else {
    title << "display mode: -";
  }
  out << fit(title.str(), static_cast<std::size_t>(width)) << "\n";
  if (rows.empty()) {
    out << fit("(no component has reported yet: the kernel publishes wysiwyf/diagnostics once a second)",
               static_cast<std::size_t>(width))
        << "\n";
    return out.str();
  }
  const auto shown = columns_for(width);
  int used = 0;
  for (const Column* c : shown) {
    out << (c->left ? std::left : std::right) << std::setw(c->width) << c->heading;
    used += c->width;
  }
  const auto problem_width = static_cast<std::size_t>(std::max(0, width - used - 2));
  out << (problem_width >= 7 ? "  problem" : "") << "\n";
  std::vector<std::pair<std::string, const json*>> ordered;
  std::map<std::string, double> age;
  const auto now = Clock::now();
  for (const auto& [instance, row] : rows) {
    ordered.push_back({row.first.value("process", "") + "/" + instance, &row.first});
    age[instance] = std::chrono::duration<double>(now - row.second).count();
  }
  std::sort(ordered.begin(), ordered.end());
  // (Two lines of headings; a last line says how many rows did not fit.)
  const std::size_t room = static_cast<std::size_t>(std::max(1, height - 2));
  const std::size_t listed = ordered.size() <= room ? ordered.size() : room - 1;
  for (std::size_t i = 0; i < listed; ++i) {
    const json& j = *ordered[i].second;
    const std::string instance = j.value("instance", "");
    std::string state = label(j.value("state", "?"));
    if (age[instance] > 3.0) state = "silent";  // its process stopped reporting
    std::string problem = j.value("last_error", "");
    if (problem.empty()) problem = j.value("last_warning", "");
    if (problem.empty()) problem = dropped_by_port(j);
    for (const Column* c : shown) out << (c->left ? std::left : std::right) << std::setw(c->width) << c->text(j, state);
    if (problem_width >= 7 && !problem.empty()) out << "  " << fit(problem, problem_width);
    out << "\n";
  }
  if (listed < ordered.size())
    out << fit("... " + std::to_string(ordered.size() - listed) + " more component(s): a taller terminal shows them",
               static_cast<std::size_t>(width))
        << "\n";
  return out.str();
}

}  // namespace

int cmd_monitor(Args args) {
  Session s;
  open(args, s);
  const double interval = number_option(args, "--interval", 0.5, 0.001, 3600, "a number of seconds, 0.001 to 3600");
  const double duration = number_option(args, "--duration", 0, 0, std::numeric_limits<double>::infinity(),
                                        "a number of seconds (0: until Ctrl-C)");
  const bool once = args.flag("--once");
  const std::string diagnostics_topic = "wysiwyf/diagnostics";
  const std::string mode_topic = args.value("--mode-topic").value_or("display/mode");
  if (!args.unknown_options().empty()) throw UsageError("unknown option " + args.unknown_options().front());
  install_stop_signal_handlers();
  const bool tty = isatty(STDOUT_FILENO);

  Subscriber* subscriber = s.participant->create_subscriber(SUBSCRIBER_QOS_DEFAULT);
  Latest diagnostics("wysiwyf::kernel_msgs::Diagnostics", true), mode("wysiwyf::msg::DisplayMode", false);
  bool reading_diagnostics = false, reading_mode = false;
  const auto start = Clock::now();
  auto next_draw = start;
  std::pair<int, int> drawn_size{0, 0};
  if (tty && !once) std::cout << "\x1b[2J\x1b[?25l";  // a clear screen, no cursor while redrawing
  while (!stop_signal_received() && (duration == 0 || Clock::now() - start < std::chrono::duration<double>(duration))) {
    const auto topics = s.discovery.topics();
    for (auto [topic, latest, reading] : {std::tuple{&diagnostics_topic, &diagnostics, &reading_diagnostics},
                                          std::tuple{&mode_topic, &mode, &reading_mode}}) {
      auto it = topics.find(*topic);
      if (*reading || it == topics.end() || it->second.writers.empty()) continue;
      *reading =
          open_raw_reader(s, subscriber, *topic, it->second, 64, latest, StatusMask::data_available()) != nullptr;
    }
    if (Clock::now() >= next_draw) {
      const auto rows = diagnostics.samples();
      if (once) {
        if (!rows.empty() || Clock::now() - start > std::chrono::seconds(10)) {
          std::this_thread::sleep_for(std::chrono::milliseconds(2200));  // a full window from every process
          std::cout << render(s.domain, diagnostics.samples(), mode.samples(), terminal_size()) << std::flush;
          return rows.empty() ? 1 : 0;
        }
      } else {
        const auto size = terminal_size();
        std::string table = render(s.domain, rows, mode.samples(), size);
        if (tty) {  // in place: each line cleared to its end, the rest below cleared; all of it after a resize
          for (std::size_t at = table.find('\n'); at != std::string::npos; at = table.find('\n', at + 4))
            table.replace(at, 1, "\x1b[K\n");
          if (!table.empty() && table.back() == '\n') table.pop_back();  // (no scroll on the last row)
          std::cout << (size != drawn_size ? "\x1b[2J" : "") << "\x1b[H" << table << "\x1b[K\x1b[J" << std::flush;
          drawn_size = size;
        } else {
          std::cout << table << "\n" << std::flush;  // one table after another
        }
      }
      next_draw += std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(interval));
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  if (tty && !once) std::cout << "\x1b[?25h";
  s.participant->delete_contained_entities();
  return 0;
}

}  // namespace wysiwyf::cli
