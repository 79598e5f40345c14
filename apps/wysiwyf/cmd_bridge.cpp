// wysiwyf bridge: the topics of a DDS domain to Foxglove (its WebSocket protocol: every topic
// advertised with its OMG IDL, samples streamed as CDR) and to the web dashboard, on one port.
// A topic is read from DDS only while a client subscribes to it (or the dashboard shows it), so
// the pipeline serialises nothing for topics nobody watches.
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include <algorithm>
#include <limits>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <set>
#include <thread>

#include "bridge/dashboard_feed.hpp"
#include "bridge/ws_server.hpp"
#include "dds_session.hpp"
#include "idl_schemas.hpp"
#include "raw_cdr_type.hpp"
#include "wysiwyf/dds.hpp"
#include "wysiwyf/runtime.hpp"
#include "wysiwyf/search_paths.hpp"

namespace wysiwyf::cli {

using namespace eprosima::fastdds::dds;
namespace fs = std::filesystem;

namespace {

std::uint64_t wall_ns() {
  return static_cast<std::uint64_t>(
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::system_clock::now().time_since_epoch())
          .count());
}

// The dashboard's files: --web-root, $WYSIWYF_DASHBOARD_DIR, the install's share/wysiwyf/dashboard,
// or (a program built in this tree) the source tree's apps/wysiwyf/dashboard.
fs::path find_web_root(const std::optional<std::string>& option) {
  if (option) return *option;
  if (const char* env = std::getenv("WYSIWYF_DASHBOARD_DIR"); env && *env) return env;
  std::error_code ec;
  const fs::path exe = program_dir();
  for (const fs::path& candidate :
       {exe.parent_path() / "share" / "wysiwyf" / "dashboard", fs::path(WYSIWYF_SOURCE_DASHBOARD_DIR)})
    if (fs::is_regular_file(candidate / "index.html", ec)) return candidate;
  return {};
}

// One bridged topic: its channel, and a reader of raw CDR while someone wants it.
class BridgedTopic final : public DataReaderListener {
 public:
  // `stamped`: the type's first member is a Header (idl_schemas.hpp), so each sample carries its
  // time on the pipeline's clock; `clock`: the newest such time seen on any topic (0: none yet).
  BridgedTopic(Session& session, bridge::WsServer& server, bridge::DashboardFeed& feed, std::string topic,
               TopicInfo info, std::uint32_t channel, bool stamped, std::atomic<std::uint64_t>& clock)
      : session_(session),
        server_(server),
        feed_(feed),
        topic_(std::move(topic)),
        info_(std::move(info)),
        channel_(channel),
        stamped_(stamped),
        clock_(clock) {}

  // Each sample goes out stamped on the pipeline's clock (its own stamp, else the pipeline's
  // newest time, else the wall clock), as the Time messages tell Foxglove that clock.
  void on_data_available(DataReader* reader) override {
    SampleInfo si;
    while (reader->take_next_sample(&sample_, &si) == ReturnCode_t::RETCODE_OK) {
      if (!si.valid_data) continue;
      std::uint64_t t = stamp_of(sample_.bytes);
      if (t > 0) {
        for (std::uint64_t seen = clock_.load(); t > seen && !clock_.compare_exchange_weak(seen, t);) {
        }
      } else {
        t = clock_.load();
      }
      if (t == 0) t = wall_ns();
      server_.publish(channel_, t, sample_.bytes.data(), sample_.bytes.size());
      if (to_dashboard) feed_.on_sample(topic_, info_.type, sample_.bytes, t);
    }
  }
  // A writer whose QoS this reader cannot match (a replay's after the live writer's): the main
  // loop opens the reader again with the topic's QoS as its writers now announce it.
  void on_requested_incompatible_qos(DataReader*, const RequestedIncompatibleQosStatus& status) override {
    std::lock_guard<std::mutex> lock(refused_mutex_);
    refused_ = dds::qos_policy_name(status.last_policy_id);
  }

  // Opens or closes the reader; an open one whose writer was refused is opened again with `now`,
  // the topic as discovery sees it now, and every Foxglove client is told.
  void want(bool wanted, Subscriber* subscriber, const TopicInfo& now) {
    std::string refused;
    {
      std::lock_guard<std::mutex> lock(refused_mutex_);
      refused.swap(refused_);
    }
    // (Only for a change: two writers of conflicting QoS at once keep one of them refused.)
    const bool other_qos = now.reliability != info_.reliability || now.durability != info_.durability ||
                           now.one_writer != info_.one_writer || now.keyed != info_.keyed;
    if (!refused.empty() && reader_ && wanted && other_qos) {
      subscriber->delete_datareader(reader_);
      reader_ = nullptr;
      info_ = now;
      const std::string text = "topic '" + topic_ + "': a writer was refused (" + refused +
                               "); the bridge reads it again with the QoS its writers announce now";
      std::cerr << text << "\n";
      server_.status_to_foxglove(1, text);
    }
    if (wanted == (reader_ != nullptr)) return;
    if (!wanted) {
      subscriber->delete_datareader(reader_);
      reader_ = nullptr;
      return;
    }
    info_ = now;
    reader_ = open_raw_reader(session_, subscriber, topic_, info_, 32, this,
                              StatusMask::data_available() << StatusMask::requested_incompatible_qos());
  }

  std::atomic<bool> to_dashboard{false};
  std::uint32_t channel() const { return channel_; }

 private:
  Session& session_;
  bridge::WsServer& server_;
  bridge::DashboardFeed& feed_;
  std::string topic_;
  TopicInfo info_;
  std::uint32_t channel_;
  // A stamped sample's stamp, 0 where there is none or it is not a time on the pipeline's clock.
  std::uint64_t stamp_of(const std::vector<std::uint8_t>& cdr) const {
    const auto ns = stamped_ ? header_stamp(cdr) : std::nullopt;
    return ns && *ns > 0 ? static_cast<std::uint64_t>(*ns) : 0;
  }

  bool stamped_;
  std::atomic<std::uint64_t>& clock_;
  RawCdr sample_;
  DataReader* reader_ = nullptr;
  std::mutex refused_mutex_;
  std::string refused_;  // the policy of the last refused writer, until the main loop acts
};

}  // namespace

int cmd_bridge(Args args) {
  Session s;
  open(args, s);
  bridge::ServerOptions server_options;
  server_options.address = args.value("--address").value_or("127.0.0.1");
  server_options.port = static_cast<std::uint16_t>(
      whole_option(args, "--port", server_options.port, 0, 65535, "a TCP port, 0-65535 (0: any free one)"));
  server_options.web_root = find_web_root(args.value("--web-root"));
  bridge::DashboardOptions dash;
  dash.domain = s.domain;
  if (auto v = args.value("--video")) dash.video_topic = *v;
  if (auto plots = args.values("--plot"); !plots.empty()) dash.plots = plots;
  for (const auto& p : dash.plots)
    if (p.find(':') == std::string::npos)
      throw UsageError("--plot: found '" + p + "'; expected TOPIC:FIELD, e.g. robot/wrench:wrench.force.z");
  const double duration = number_option(args, "--duration", 0, 0, std::numeric_limits<double>::infinity(),
                                        "a number of seconds (0: until Ctrl-C)");
  const std::vector<std::string> only = args.positional();
  if (!args.unknown_options().empty()) throw UsageError("unknown option " + args.unknown_options().front());
  install_stop_signal_handlers();

  std::mutex wanted_mutex;  // (before the server: its I/O thread uses them until it stops)
  std::set<std::uint32_t> foxglove_wanted;
  bridge::WsServer server(server_options);
  bridge::DashboardFeed feed(server, dash);
  server.on_channel_wanted = [&](std::uint32_t channel, bool wanted) {
    std::lock_guard<std::mutex> lock(wanted_mutex);
    if (wanted)
      foxglove_wanted.insert(channel);
    else
      foxglove_wanted.erase(channel);
  };
  server.on_dashboard_request = [&](const bridge::DashboardRequest& request) { feed.on_request(request); };
  server.dashboard_greeting = [&] { return feed.greeting(); };
  server.start();
  const std::string host = server_options.address == "0.0.0.0" ? "localhost" : server_options.address;
  std::cout << "bridging domain " << s.domain << " (transport " << s.transport << ")\n"
            << "  Foxglove: open a Foxglove WebSocket connection to ws://" << host << ":" << server.port() << "\n"
            << "  dashboard: http://" << host << ":" << server.port() << "/"
            << (server_options.web_root.empty() ? " (not served: its files were not found; --web-root DIR)" : "")
            << "\n"
            << std::flush;

  Subscriber* subscriber = s.participant->create_subscriber(SUBSCRIBER_QOS_DEFAULT);
  s.discovery.name_participant(*s.participant);  // (its readers in the connection graph)
  std::map<std::string, std::unique_ptr<BridgedTopic>> topics;
  std::uint32_t next_channel = 1;
  bool told_too_many = false;
  std::atomic<std::uint64_t> pipeline_clock{0};  // (before the topics that write it)
  std::uint64_t clock_sent = 0;
  const auto start = Clock::now();
  while (!stop_signal_received() && (duration == 0 || Clock::now() - start < std::chrono::duration<double>(duration))) {
    // New topics as writers announce them: a channel each, with its type's IDL as the schema.
    for (const auto& [topic, info] : s.discovery.topics()) {
      if (info.writers.empty() || topics.count(topic)) continue;
      if (!only.empty() && std::find(only.begin(), only.end(), topic) == only.end()) continue;
      if (next_channel >= bridge::kMaxChannels) {  // any participant may announce topics: bounded
        if (!told_too_many)
          std::cerr << "more than " << bridge::kMaxChannels - 1 << " topics: the rest are not bridged\n";
        told_too_many = true;
        continue;
      }
      std::string searched;
      const auto schema = idl_schema(info.type, searched);
      if (!schema)
        std::cerr << "topic '" << topic << "': no IDL defines " << info.type << " (searched " << searched
                  << "); advertised without a schema\n";
      bridge::Channel channel;
      channel.id = next_channel++;
      channel.topic = topic;
      channel.schema_name = info.type;
      channel.schema = schema ? schema->text : "";
      server.advertise(channel);
      topics.emplace(topic, std::make_unique<BridgedTopic>(s, server, feed, topic, info, channel.id,
                                                           schema && schema->stamped, pipeline_clock));
    }
    // Readers for what is wanted now, none for the rest.
    const auto dashboard_topics = feed.wanted_topics();
    std::set<std::uint32_t> fox;
    {
      std::lock_guard<std::mutex> lock(wanted_mutex);
      fox = foxglove_wanted;
    }
    const auto discovered = s.discovery.topics();
    for (auto& [topic, bridged] : topics) {
      bridged->to_dashboard = dashboard_topics.count(topic) > 0;
      const auto now = discovered.find(topic);
      if (now != discovered.end())
        bridged->want(bridged->to_dashboard || fox.count(bridged->channel()), subscriber, now->second);
    }
    feed.flush();
    // Who publishes and subscribes what, by participant name; and the pipeline's clock.
    bridge::ConnectionGraph graph;
    for (const auto& [topic, info] : discovered) {
      auto& publishers = graph.published[topic];
      auto& subscribers = graph.subscribed[topic];
      for (const auto& w : info.writers) {
        publishers.insert(s.discovery.participant_of(w));
        // a process that reads what it writes, in-process
        if (const auto it = info.ports.find(w); it != info.ports.end() && it->second.readers > 0)
          subscribers.insert(s.discovery.participant_of(w));
      }
      for (const auto& r : info.readers) subscribers.insert(s.discovery.participant_of(r));
    }
    server.connection_graph(std::move(graph));
    if (const std::uint64_t now = pipeline_clock.load(); now != clock_sent) {
      server.time(now);
      clock_sent = now;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  server.stop();                               // no server callback runs after this
  s.participant->delete_contained_entities();  // nor a listener
  const auto st = server.stats();
  std::cout << "bridge: " << topics.size() << " topics advertised, " << st.messages_sent << " messages sent, "
            << st.messages_dropped << " dropped for slow clients\n";
  return 0;
}

}  // namespace wysiwyf::cli
