#pragma once
// What the web dashboard shows, made from the samples the bridge reads: the component table
// (the kernel's wysiwyf/diagnostics), the display mode, live plots of chosen fields, and the
// composite video as JPEG. Sent to the dashboard clients of a WsServer as JSON ops:
//   {"op":"hello", domain, video, plots}           on connection, then the table and mode so far
//   {"op":"diagnostics", "sample":{...}}           one component's Diagnostics, as echo prints it
//   {"op":"mode", "sample":{...}}                  the display mode (when it changes, else <= 5 Hz)
//   {"op":"points", "plot":"topic:field", "t":[s], "v":[...]}  plot data, batched every 100 ms
//   binary: a JPEG of the video topic (<= 10 per second)
// and requests from the page: {"op":"plot","topic":T,"field":F}, {"op":"unplot",...}.
#include <chrono>
#include <cstdint>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "sample_json.hpp"
#include "ws_server.hpp"

namespace wysiwyf::bridge {

struct DashboardOptions {
  int domain = 0;
  std::string diagnostics_topic = "wysiwyf/diagnostics";
  std::string mode_topic = "display/mode";
  std::string video_topic = "display/view";
  std::vector<std::string> plots = {"robot/wrench:wrench.force.z", "robot/joint_state:velocity.2"};  // topic:field
};

class DashboardFeed {
 public:
  DashboardFeed(WsServer& server, DashboardOptions options);

  // The topics it needs read now (diagnostics and mode always; video and plots while a page is open).
  std::set<std::string> wanted_topics() const;
  // A sample of `topic` (any thread; the bridge calls it for the topics above).
  void on_sample(const std::string& topic, const std::string& type, const std::vector<std::uint8_t>& cdr,
                 std::uint64_t receive_ns);
  // Sends what is batched (the bridge calls it every few tens of ms).
  void flush();

  // The WsServer's dashboard hooks.
  std::vector<std::string> greeting();
  void on_request(const DashboardRequest& request);

 private:
  struct Plot {
    std::string topic, field;
    std::vector<double> t, v;
    std::chrono::steady_clock::time_point last{};
  };
  void add_plot(const std::string& topic, const std::string& field);
  void video_frame(const msg::Image& image);

  WsServer& server_;
  DashboardOptions options_;
  mutable std::mutex mutex_;
  SampleDecoder decoder_;
  std::map<std::string, std::string> diagnostics_;  // instance -> last op text
  std::string mode_;                                // last mode op text
  std::string mode_name_;
  std::chrono::steady_clock::time_point mode_sent_{}, frame_sent_{};
  std::map<std::string, Plot> plots_;  // "topic:field"
};

}  // namespace wysiwyf::bridge
