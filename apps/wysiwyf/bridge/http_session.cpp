#include "http_session.hpp"

#include <boost/beast/websocket.hpp>
#include <chrono>
#include <memory>
#include <sstream>

#include "web_files.hpp"

namespace wysiwyf::bridge {

namespace beast = boost::beast;
namespace http = beast::http;
using tcp = boost::asio::ip::tcp;

namespace {

class HttpSession : public std::enable_shared_from_this<HttpSession> {
 public:
  HttpSession(tcp::socket&& socket, std::filesystem::path web_root, std::vector<std::string> subprotocols,
              WsUpgrade upgrade)
      : stream_(std::move(socket)),
        web_root_(std::move(web_root)),
        subprotocols_(std::move(subprotocols)),
        upgrade_(std::move(upgrade)) {}

  void read() {
    req_ = {};
    stream_.expires_after(std::chrono::seconds(30));
    http::async_read(stream_, buffer_, req_,
                     [self = shared_from_this()](beast::error_code ec, std::size_t) { self->on_read(ec); });
  }

 private:
  // The subprotocol the server speaks out of a client's offer ("a, b"), or "" if none.
  std::string pick_subprotocol(const std::string& offered) const {
    std::stringstream in(offered);
    std::string item;
    while (std::getline(in, item, ',')) {
      const auto b = item.find_first_not_of(' '), e = item.find_last_not_of(' ');
      if (b == std::string::npos) continue;
      const std::string p = item.substr(b, e - b + 1);
      for (const auto& ours : subprotocols_)
        if (p == ours) return p;
    }
    return "";
  }

  void on_read(beast::error_code ec) {
    if (ec) return;
    if (beast::websocket::is_upgrade(req_)) {
      const std::string protocol = pick_subprotocol(std::string(req_[http::field::sec_websocket_protocol]));
      if (protocol.empty()) {
        std::string expected;
        for (const auto& p : subprotocols_) expected += (expected.empty() ? "" : " or ") + p;
        respond(http::status::bad_request, "text/plain", "expected the WebSocket subprotocol " + expected + "\n");
        return;
      }
      stream_.expires_never();
      upgrade_(std::move(stream_), std::move(req_), protocol);
      return;
    }
    serve_file();
  }

  void serve_file() {
    if (req_.method() != http::verb::get && req_.method() != http::verb::head) {
      respond(http::status::method_not_allowed, "text/plain", "only GET\n");
      return;
    }
    std::string problem;
    const auto target = req_.target();
    const auto file = resolve_web_file(web_root_, std::string_view(target.data(), target.size()), problem);
    const auto body = file ? read_web_file(*file) : std::nullopt;
    if (!body) {
      // The client learns only that there is no such file; the target is not echoed.
      respond(http::status::not_found, "text/plain",
              web_root_.empty() ? "not found (this bridge serves no dashboard)\n" : "not found\n");
      return;
    }
    respond(http::status::ok, web_content_type(file->path), *body);
  }

  void respond(http::status status, const std::string& type, std::string body) {
    auto res = std::make_shared<http::response<http::string_body>>(status, req_.version());
    res->set(http::field::server, "wysiwyf bridge");
    res->set(http::field::content_type, type);
    res->set(http::field::cache_control, "no-cache");
    res->keep_alive(req_.keep_alive());
    res->body() = req_.method() == http::verb::head ? "" : std::move(body);
    res->prepare_payload();
    http::async_write(stream_, *res, [self = shared_from_this(), res](beast::error_code ec, std::size_t) {
      if (!ec && res->keep_alive()) self->read();
    });
  }

  beast::tcp_stream stream_;
  beast::flat_buffer buffer_;
  HttpRequest req_;
  std::filesystem::path web_root_;
  std::vector<std::string> subprotocols_;
  WsUpgrade upgrade_;
};

}  // namespace

void serve_http(tcp::socket&& socket, std::filesystem::path web_root, std::vector<std::string> subprotocols,
                WsUpgrade upgrade) {
  std::make_shared<HttpSession>(std::move(socket), std::move(web_root), std::move(subprotocols), std::move(upgrade))
      ->read();
}

}  // namespace wysiwyf::bridge
