#include "ws_server.hpp"

#include "http_session.hpp"
#include "ws_session.hpp"

namespace wysiwyf::bridge {

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
