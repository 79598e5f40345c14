#pragma once
// The bridge's network side (Boost.Beast: HTTP and WebSocket on one port, in Debian's Boost):
// the Foxglove WebSocket protocol v1 (subprotocol "foxglove.websocket.v1": advertise channels,
// clients subscribe, message data streamed as binary frames), the dashboard's own feed
// (subprotocol "wysiwyf.dashboard.v1": JSON and JPEG frames), and the dashboard's files over
// plain HTTP (only the files of its web root: web_files.hpp). Every client request is validated
// before use (client_requests.hpp), bounded in size and rate; a bad one gets a reply naming what
// was wrong and the server carries on. One I/O thread; publishing from any thread never blocks: a client that cannot keep
// up loses messages (counted, and told once in a status message) instead of holding DDS back.
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "client_requests.hpp"
#include "connection_graph.hpp"

namespace wysiwyf::bridge {

constexpr std::uint32_t kMaxChannels = 4096;  // channel ids are 1 to kMaxChannels - 1

struct Channel {
  std::uint32_t id = 0;
  std::string topic;
  std::string encoding = "cdr";
  std::string schema_name;
  std::string schema;  // the schema text ("" when none is known)
  std::string schema_encoding = "omgidl";
};

struct ServerOptions {
  std::string address = "127.0.0.1";
  std::uint16_t port = 8765;       // 0: any free port (port() says which)
  std::filesystem::path web_root;  // the dashboard's files ("" serves none)
  std::string name = "wysiwyf bridge";
  std::size_t client_queue_bytes = 64u << 20;  // beyond this a client's message data is dropped
};

struct ServerStats {
  std::size_t foxglove_clients = 0, dashboard_clients = 0;
  std::uint64_t messages_sent = 0, messages_dropped = 0;
};

class WsServer {
 public:
  explicit WsServer(ServerOptions options);  // binds (throws, saying why, if it cannot)
  ~WsServer();
  // Accepts clients from now on, on the I/O thread: set the callbacks below first.
  void start();
  // Closes every client and stops the I/O thread (the destructor does too): no callback runs after.
  void stop();
  WsServer(const WsServer&) = delete;
  WsServer& operator=(const WsServer&) = delete;

  std::uint16_t port() const;

  // Foxglove: channels are advertised to every client, now and on connection.
  void advertise(const Channel& channel);
  void unadvertise(std::uint32_t channel_id);
  // Message data to the clients subscribed to `channel_id` (copied; returns at once).
  void publish(std::uint32_t channel_id, std::uint64_t receive_ns, const std::uint8_t* data, std::size_t size);
  // The domain's graph now: sent (what changed) to the Foxglove clients subscribed to it.
  void connection_graph(ConnectionGraph graph);
  // The pipeline's clock now (ns; sim time on the sim clock): a Time message to every Foxglove
  // client (the `time` capability), so Foxglove's clock follows the pipeline's.
  void time(std::uint64_t ns);
  // A status message to every Foxglove client (level 0 info, 1 warning, 2 error).
  void status_to_foxglove(int level, const std::string& message);
  // How many Foxglove subscriptions `channel_id` has (0: nobody wants it; cheap, any thread).
  int subscribers(std::uint32_t channel_id) const;
  // Called on the I/O thread when a channel gains its first or loses its last subscriber.
  std::function<void(std::uint32_t channel_id, bool wanted)> on_channel_wanted;

  // Dashboard clients: a JSON text or a binary frame to all of them.
  void dashboard_text(std::string json);
  void dashboard_binary(std::vector<std::uint8_t> bytes);
  // A dashboard client's request, validated (the I/O thread calls it; a bad one never reaches
  // it: the client is told what was wrong).
  std::function<void(const DashboardRequest& request)> on_dashboard_request;
  // Called (I/O thread) when a dashboard client connects: what it should be sent first.
  std::function<std::vector<std::string>()> dashboard_greeting;

  ServerStats stats() const;

  struct Impl;  // (ws_server.cpp: the sessions reach it)

 private:
  std::shared_ptr<Impl> impl_;
  std::thread io_thread_;
};

}  // namespace wysiwyf::bridge
