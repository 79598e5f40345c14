#include "ws_server.hpp"

#include <array>
#include <boost/asio.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <chrono>
#include <deque>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>

#include "client_requests.hpp"
#include "http_session.hpp"

namespace wysiwyf::bridge {

namespace net = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
using tcp = net::ip::tcp;
using json = nlohmann::json;

namespace {

constexpr const char* kFoxglove = "foxglove.websocket.v1";
constexpr const char* kDashboard = "wysiwyf.dashboard.v1";
// Requests a client may make: 50 a second, bursts of 200 (a page subscribing to every channel at
// once sends one request); beyond that they are refused and the client told.
constexpr double kRequestsPerSecond = 50, kRequestBurst = 200;

// JSON text for a client; a string that is not UTF-8 (a topic or type name from any participant
// on the domain may hold any bytes) is replaced rather than thrown on.
std::string to_text(const json& j) { return j.dump(-1, ' ', false, json::error_handler_t::replace); }

std::string channel_json(const Channel& c) {
  return to_text(json{{"id", c.id},
                      {"topic", c.topic},
                      {"encoding", c.encoding},
                      {"schemaName", c.schema_name},
                      {"schema", c.schema},
                      {"schemaEncoding", c.schema_encoding}});
}

}  // namespace

class WsSession;

struct WsServer::Impl {
  ServerOptions options;
  WsServer* owner = nullptr;
  net::io_context io;
  tcp::acceptor acceptor{io};
  // I/O thread only.
  std::map<std::uint32_t, Channel> channels;
  ConnectionGraph graph;
  std::set<std::shared_ptr<WsSession>> sessions;
  // Any thread.
  std::unique_ptr<std::atomic<int>[]> subscriber_counts { new std::atomic<int>[ kMaxChannels ]() };
  std::atomic<std::uint64_t> sent{0}, dropped{0};
  std::atomic<std::size_t> foxglove_clients{0}, dashboard_clients{0};

  void accept();
  void subscribed(std::uint32_t channel, int change) {
    const int now = subscriber_counts[channel].fetch_add(change) + change;
    if (owner->on_channel_wanted && ((change > 0 && now == 1) || (change < 0 && now == 0)))
      owner->on_channel_wanted(channel, now > 0);
  }
};

// One WebSocket client, Foxglove or dashboard.
class WsSession : public std::enable_shared_from_this<WsSession> {
 public:
  WsSession(beast::tcp_stream&& stream, std::shared_ptr<WsServer::Impl> server, std::string protocol)
      : ws_(std::move(stream)), server_(std::move(server)), protocol_(std::move(protocol)) {}

  bool foxglove() const { return protocol_ == kFoxglove; }
  bool graph_subscribed() const { return graph_subscribed_; }

  void accept(http::request<http::string_body> req) {
    ws_.set_option(websocket::stream_base::timeout::suggested(beast::role_type::server));
    ws_.read_message_max(kMaxRequestBytes);  // a larger message closes this client ("message too big")
    ws_.set_option(websocket::stream_base::decorator([p = protocol_](websocket::response_type& res) {
      res.set(http::field::sec_websocket_protocol, p);
      res.set(http::field::server, "wysiwyf bridge");
    }));
    ws_.async_accept(req, [self = shared_from_this()](beast::error_code ec) { self->on_accept(ec); });
  }

  void send_text(std::string text) {
    enqueue({"", std::make_shared<const std::string>(std::move(text)), false, false});
  }
  // Message data of a channel this client subscribed to: the header is per client (it names the
  // subscription), the payload is shared by all.
  void send_message(std::uint32_t channel, std::uint64_t receive_ns,
                    const std::shared_ptr<const std::string>& payload) {
    auto it = subscription_of_channel_.find(channel);
    if (it == subscription_of_channel_.end()) return;
    std::string header(13, '\0');
    header[0] = 0x01;
    for (int i = 0; i < 4; ++i) header[1 + i] = static_cast<char>((it->second >> (8 * i)) & 0xff);
    for (int i = 0; i < 8; ++i) header[5 + i] = static_cast<char>((receive_ns >> (8 * i)) & 0xff);
    enqueue({std::move(header), payload, true, true});
  }
  void send_binary(const std::shared_ptr<const std::string>& bytes, bool droppable) {
    enqueue({"", bytes, true, droppable});
  }

  void close() {
    if (closed_) return;
    closed_ = true;
    for (const auto& [sub, channel] : channel_of_subscription_) server_->subscribed(channel, -1);
    channel_of_subscription_.clear();
    subscription_of_channel_.clear();
    (foxglove() ? server_->foxglove_clients : server_->dashboard_clients).fetch_sub(1);
    server_->sessions.erase(shared_from_this());
    beast::error_code ec;
    beast::get_lowest_layer(ws_).socket().close(ec);
  }

  void send_status(int level, const std::string& message) { status(level, message); }

 private:
  struct Frame {
    std::string header;
    std::shared_ptr<const std::string> body;
    bool binary = false;
    bool droppable = false;
  };

  void on_accept(beast::error_code ec) {
    if (ec) return;
    server_->sessions.insert(shared_from_this());
    (foxglove() ? server_->foxglove_clients : server_->dashboard_clients).fetch_add(1);
    if (foxglove()) {
      send_text(
          to_text(json{{"op", "serverInfo"},
                       {"name", server_->options.name},
                       {"capabilities", json::array({"connectionGraph", "time"})},
                       {"metadata", json{{"wysiwyf", "DDS topics as CDR with their OMG IDL"}}},
                       {"sessionId", std::to_string(std::chrono::system_clock::now().time_since_epoch().count())}}));
      std::string channels = R"({"op":"advertise","channels":[)";
      bool first = true;
      for (const auto& [id, c] : server_->channels) {
        channels += (first ? "" : ",") + channel_json(c);
        first = false;
      }
      send_text(channels + "]}");
    } else if (server_->owner->dashboard_greeting) {
      for (auto& text : server_->owner->dashboard_greeting()) send_text(std::move(text));
    }
    read();
  }

  void read() {
    ws_.async_read(buffer_, [self = shared_from_this()](beast::error_code ec, std::size_t) { self->on_read(ec); });
  }
  void on_read(beast::error_code ec) {
    if (ec) {
      close();
      return;
    }
    if (!budget_.take(RequestBudget::Clock::now())) {
      if (budget_.refusal_to_report())
        problem("more than " + std::to_string(static_cast<int>(kRequestsPerSecond)) +
                " requests a second: the rest are refused until this client slows down");
    } else if (!ws_.got_text()) {
      problem(foxglove() ? "binary client messages (client publish, service calls) are not supported by this server"
                         : "the dashboard takes JSON text requests only");
    } else {
      const std::string text = beast::buffers_to_string(buffer_.data());
      if (foxglove())
        handle_foxglove(text);
      else
        handle_dashboard(text);
    }
    buffer_.consume(buffer_.size());
    read();
  }

  // Tells this client what was wrong with its request: a Foxglove status (level 2, error) or the
  // dashboard's {"op":"error"}. Droppable: a client that sends without reading cannot grow its
  // queue with replies beyond the queue's bound.
  void problem(const std::string& message) { status(2, message); }
  void status(int level, const std::string& message) {
    const json reply = foxglove() ? json{{"op", "status"}, {"level", level}, {"message", message}}
                                  : json{{"op", "error"}, {"message", message}};
    enqueue({"", std::make_shared<const std::string>(to_text(reply)), false, true});
  }

  void handle_dashboard(const std::string& text) {
    const DashboardRequest r = parse_dashboard_request(text);
    if (r.op == DashboardRequest::Op::kInvalid)
      problem(r.problem);
    else if (server_->owner->on_dashboard_request)
      server_->owner->on_dashboard_request(r);
  }

  void handle_foxglove(const std::string& text) {
    const FoxgloveRequest r = parse_foxglove_request(text);
    if (r.op == FoxgloveRequest::Op::kSubscribe) {
      // One reply for all the refused subscriptions of a request, naming the first.
      std::size_t refused = 0;
      std::string first;
      for (const auto [id, channel] : r.subscriptions) {
        std::string why;
        if (!server_->channels.count(channel))
          why = "no channel " + std::to_string(channel) + " is advertised";
        else if (channel_of_subscription_.count(id))
          why = "subscription id " + std::to_string(id) + " is in use";
        else if (subscription_of_channel_.count(channel))
          why = "channel " + std::to_string(channel) + " is already subscribed by this client";
        if (why.empty()) {
          channel_of_subscription_[id] = channel;
          subscription_of_channel_[channel] = id;
          server_->subscribed(channel, +1);
        } else if (refused++ == 0) {
          first = why;
        }
      }
      if (refused == 1) status(2, "subscribe: " + first);
      if (refused > 1)
        status(2, "subscribe: " + std::to_string(refused) + " subscriptions refused, the first: " + first);
    } else if (r.op == FoxgloveRequest::Op::kSubscribeGraph) {
      graph_subscribed_ = true;  // the whole graph now, then what changes
      const std::string full = connection_graph_update({}, server_->graph);
      if (!full.empty()) send_text(full);
    } else if (r.op == FoxgloveRequest::Op::kUnsubscribeGraph) {
      graph_subscribed_ = false;
    } else if (r.op == FoxgloveRequest::Op::kUnsubscribe) {
      for (const std::uint32_t id : r.unsubscribe) {
        auto it = channel_of_subscription_.find(id);
        if (it == channel_of_subscription_.end()) continue;
        subscription_of_channel_.erase(it->second);
        server_->subscribed(it->second, -1);
        channel_of_subscription_.erase(it);
      }
    } else {
      status(r.op == FoxgloveRequest::Op::kUnsupported ? 1 : 2, r.problem);
    }
  }

  void enqueue(Frame f) {
    if (closed_) return;
    const std::size_t size = f.header.size() + f.body->size();
    if (f.droppable && queued_bytes_ + size > server_->options.client_queue_bytes) {
      server_->dropped.fetch_add(1);
      if (!warned_drops_ && foxglove()) {
        warned_drops_ = true;
        status(1, "this client reads slower than the topics come: messages are being dropped");
      }
      return;
    }
    queued_bytes_ += size;
    queue_.push_back(std::move(f));
    if (!writing_) write_next();
  }
  void write_next() {
    writing_ = true;
    Frame& f = queue_.front();
    ws_.binary(f.binary);
    const std::array<net::const_buffer, 2> buffers{net::buffer(f.header), net::buffer(*f.body)};
    ws_.async_write(buffers, [self = shared_from_this()](beast::error_code ec, std::size_t) { self->on_write(ec); });
  }
  void on_write(beast::error_code ec) {
    queued_bytes_ -= queue_.front().header.size() + queue_.front().body->size();
    queue_.pop_front();
    server_->sent.fetch_add(1);
    if (ec) {
      close();
      return;
    }
    if (queue_.empty())
      writing_ = false;
    else
      write_next();
  }

  websocket::stream<beast::tcp_stream> ws_;
  beast::flat_buffer buffer_;
  std::shared_ptr<WsServer::Impl> server_;
  std::string protocol_;
  std::map<std::uint32_t, std::uint32_t> channel_of_subscription_, subscription_of_channel_;
  RequestBudget budget_{kRequestsPerSecond, kRequestBurst};
  std::deque<Frame> queue_;
  std::size_t queued_bytes_ = 0;
  bool writing_ = false, closed_ = false, warned_drops_ = false, graph_subscribed_ = false;
};

void WsServer::Impl::accept() {
  acceptor.async_accept(net::make_strand(io), [this](beast::error_code ec, tcp::socket socket) {
    if (ec == net::error::operation_aborted) return;
    if (!ec) {
      socket.set_option(tcp::no_delay(true));
      // The Impl outlives every session: the destructor stops the I/O thread before it goes.
      serve_http(std::move(socket), options.web_root, {kFoxglove, kDashboard},
                 [server = std::shared_ptr<Impl>(owner->impl_)](beast::tcp_stream&& stream, HttpRequest&& request,
                                                                const std::string& protocol) {
                   std::make_shared<WsSession>(std::move(stream), server, protocol)->accept(std::move(request));
                 });
    }
    accept();
  });
}

WsServer::WsServer(ServerOptions options) : impl_(std::make_shared<Impl>()) {
  impl_->options = std::move(options);
  impl_->owner = this;
  beast::error_code ec;
  const auto address = net::ip::make_address(impl_->options.address, ec);
  if (ec) throw std::runtime_error("--address: '" + impl_->options.address + "' is not an IP address");
  const tcp::endpoint endpoint(address, impl_->options.port);
  impl_->acceptor.open(endpoint.protocol(), ec);
  if (!ec) impl_->acceptor.set_option(net::socket_base::reuse_address(true), ec);
  if (!ec) impl_->acceptor.bind(endpoint, ec);
  if (!ec) impl_->acceptor.listen(net::socket_base::max_listen_connections, ec);
  if (ec)
    throw std::runtime_error("cannot listen on " + impl_->options.address + ":" + std::to_string(impl_->options.port) +
                             ": " + ec.message() + " (another bridge there? --port picks another)");
}

void WsServer::start() {
  impl_->accept();
  io_thread_ = std::thread([impl = impl_] { impl->io.run(); });
}

WsServer::~WsServer() { stop(); }

void WsServer::stop() {
  if (!io_thread_.joinable()) return;
  net::post(impl_->io, [impl = impl_] {
    beast::error_code ec;
    impl->acceptor.close(ec);
    for (auto s : std::set<std::shared_ptr<WsSession>>(impl->sessions)) s->close();
    impl->io.stop();
  });
  io_thread_.join();
}

std::uint16_t WsServer::port() const { return impl_->acceptor.local_endpoint().port(); }

void WsServer::advertise(const Channel& channel) {
  if (channel.id >= kMaxChannels) throw std::runtime_error("too many channels (at most 4096)");
  net::post(impl_->io, [impl = impl_, channel] {
    impl->channels[channel.id] = channel;
    const std::string text = R"({"op":"advertise","channels":[)" + channel_json(channel) + "]}";
    for (const auto& s : impl->sessions)
      if (s->foxglove()) s->send_text(text);
  });
}

void WsServer::unadvertise(std::uint32_t channel_id) {
  net::post(impl_->io, [impl = impl_, channel_id] {
    impl->channels.erase(channel_id);
    const std::string text = to_text(json{{"op", "unadvertise"}, {"channelIds", {channel_id}}});
    for (const auto& s : impl->sessions)
      if (s->foxglove()) s->send_text(text);
  });
}

void WsServer::connection_graph(ConnectionGraph graph) {
  net::post(impl_->io, [impl = impl_, graph = std::move(graph)]() mutable {
    const std::string update = connection_graph_update(impl->graph, graph);
    impl->graph = std::move(graph);
    if (update.empty()) return;
    for (const auto& s : impl->sessions)
      if (s->foxglove() && s->graph_subscribed()) s->send_text(update);
  });
}

void WsServer::time(std::uint64_t ns) {
  auto frame = std::make_shared<std::string>(9, '\0');
  (*frame)[0] = 0x02;  // Time: opcode, then the timestamp as uint64 little-endian
  for (int i = 0; i < 8; ++i) (*frame)[1 + i] = static_cast<char>((ns >> (8 * i)) & 0xff);
  net::post(impl_->io, [impl = impl_, frame] {
    for (const auto& s : impl->sessions)
      if (s->foxglove()) s->send_binary(frame, true);
  });
}

void WsServer::status_to_foxglove(int level, const std::string& message) {
  net::post(impl_->io, [impl = impl_, level, message] {
    for (const auto& s : impl->sessions)
      if (s->foxglove()) s->send_status(level, message);
  });
}

int WsServer::subscribers(std::uint32_t channel_id) const {
  return channel_id < kMaxChannels ? impl_->subscriber_counts[channel_id].load() : 0;
}

void WsServer::publish(std::uint32_t channel_id, std::uint64_t receive_ns, const std::uint8_t* data, std::size_t size) {
  if (subscribers(channel_id) == 0) return;
  auto payload = std::make_shared<const std::string>(reinterpret_cast<const char*>(data), size);
  net::post(impl_->io, [impl = impl_, channel_id, receive_ns, payload] {
    for (const auto& s : impl->sessions)
      if (s->foxglove()) s->send_message(channel_id, receive_ns, payload);
  });
}

void WsServer::dashboard_text(std::string text) {
  auto shared = std::make_shared<std::string>(std::move(text));
  net::post(impl_->io, [impl = impl_, shared] {
    for (const auto& s : impl->sessions)
      if (!s->foxglove()) s->send_text(*shared);
  });
}

void WsServer::dashboard_binary(std::vector<std::uint8_t> bytes) {
  auto shared = std::make_shared<const std::string>(bytes.begin(), bytes.end());
  net::post(impl_->io, [impl = impl_, shared] {
    for (const auto& s : impl->sessions)
      if (!s->foxglove()) s->send_binary(shared, true);
  });
}

ServerStats WsServer::stats() const {
  ServerStats s;
  s.foxglove_clients = impl_->foxglove_clients.load();
  s.dashboard_clients = impl_->dashboard_clients.load();
  s.messages_sent = impl_->sent.load();
  s.messages_dropped = impl_->dropped.load();
  return s;
}

}  // namespace wysiwyf::bridge
