#pragma once
// The bridge's server state and one WebSocket client of it (Foxglove or dashboard), for
// ws_server.cpp alone: the client's requests validated (client_requests.hpp), its send queue
// bounded, its replies droppable.
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
#include "ws_server.hpp"

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

}  // namespace wysiwyf::bridge
