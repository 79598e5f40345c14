// A Foxglove client that subscribes to every channel a bridge advertises and only counts what
// arrives: the "bridge streaming everything" condition of bench_monitor, in its own process as
// Foxglove would be. Prints "received N messages, B bytes" every 1000 messages.
//   foxglove_sink PORT
#include <boost/asio/connect.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/websocket.hpp>
#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>

namespace beast = boost::beast;
namespace websocket = beast::websocket;
using tcp = boost::asio::ip::tcp;

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: foxglove_sink PORT\n");
    return 2;
  }
  boost::asio::io_context io;
  websocket::stream<tcp::socket> ws(io);
  tcp::resolver resolver(io);
  // The bridge may still be starting: try for 10 s.
  for (int attempt = 0;; ++attempt) {
    beast::error_code ec;
    boost::asio::connect(ws.next_layer(), resolver.resolve("127.0.0.1", argv[1]), ec);
    if (!ec) break;
    if (attempt == 100) {
      std::fprintf(stderr, "foxglove_sink: cannot connect to port %s: %s\n", argv[1], ec.message().c_str());
      return 1;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  ws.set_option(websocket::stream_base::decorator([](websocket::request_type& req) {
    req.set(beast::http::field::sec_websocket_protocol, "foxglove.websocket.v1");
  }));
  ws.handshake("127.0.0.1", "/");
  std::uint32_t next_subscription = 0;
  std::uint64_t messages = 0, bytes = 0;
  beast::flat_buffer buffer;
  for (;;) {
    ws.read(buffer);
    if (ws.got_text()) {
      const auto m = nlohmann::json::parse(beast::buffers_to_string(buffer.data()), nullptr, false);
      if (m.is_object() && m.value("op", "") == "advertise") {
        nlohmann::json subscriptions = nlohmann::json::array();
        for (const auto& c : m["channels"])
          subscriptions.push_back({{"id", next_subscription++}, {"channelId", c["id"]}});
        ws.text(true);
        ws.write(boost::asio::buffer(nlohmann::json{{"op", "subscribe"}, {"subscriptions", subscriptions}}.dump()));
      }
    } else {
      ++messages;
      bytes += buffer.size();
      if (messages % 1000 == 0) {
        std::printf("received %llu messages, %llu bytes\n", static_cast<unsigned long long>(messages),
                    static_cast<unsigned long long>(bytes));
        std::fflush(stdout);
      }
    }
    buffer.consume(buffer.size());
  }
}
