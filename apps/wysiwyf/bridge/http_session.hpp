#pragma once
// One plain HTTP connection to the bridge: GET and HEAD of the dashboard's files (only those of
// the web root: web_files.hpp), or a WebSocket upgrade offering one of the server's subprotocols,
// handed to `upgrade` with the request. Anything else gets a 4xx that does not echo the target.
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core/tcp_stream.hpp>
#include <boost/beast/http.hpp>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace wysiwyf::bridge {

using HttpRequest = boost::beast::http::request<boost::beast::http::string_body>;
using WsUpgrade =
    std::function<void(boost::beast::tcp_stream&& stream, HttpRequest&& request, const std::string& protocol)>;

// Serves `socket` until the client closes it (or is idle 30 s between requests).
void serve_http(boost::asio::ip::tcp::socket&& socket, std::filesystem::path web_root,
                std::vector<std::string> subprotocols, WsUpgrade upgrade);

}  // namespace wysiwyf::bridge
