#pragma once
// What a bridge client may ask, read from its text frames and checked against the protocol before
// anything acts on it: a frame from a network client is hostile until shown otherwise. Parsing
// never throws and never recurses on the client's nesting; anything that is not a well-formed
// request becomes a `problem` that the server sends back to that client in a status message.
//   Foxglove (foxglove.websocket.v1): {"op":"subscribe","subscriptions":[{"id":N,"channelId":N}...]}
//                                     {"op":"unsubscribe","subscriptionIds":[N...]}
//                                     {"op":"subscribeConnectionGraph"}, {"op":"unsubscribeConnectionGraph"}
//   dashboard (wysiwyf.dashboard.v1): {"op":"plot"|"unplot","topic":"...","field":"..."}
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace wysiwyf::bridge {

constexpr std::size_t kMaxRequestBytes = 64 * 1024;  // a larger frame closes the client
constexpr int kMaxRequestDepth = 8;                  // arrays and objects nested in one request
constexpr std::size_t kMaxSubscriptionsPerRequest = 4096;
constexpr std::size_t kMaxNameBytes = 256;  // a dashboard plot's topic or field

struct Subscription {
  std::uint32_t id = 0;
  std::uint32_t channel = 0;
};

struct FoxgloveRequest {
  enum class Op { kSubscribe, kUnsubscribe, kSubscribeGraph, kUnsubscribeGraph, kUnsupported, kInvalid };
  Op op = Op::kInvalid;
  std::vector<Subscription> subscriptions;  // kSubscribe
  std::vector<std::uint32_t> unsubscribe;   // kUnsubscribe: subscription ids
  std::string problem;                      // kInvalid and kUnsupported: what to tell the client
};

struct DashboardRequest {
  enum class Op { kPlot, kUnplot, kInvalid };
  Op op = Op::kInvalid;
  std::string topic, field;
  std::string problem;  // kInvalid: what to tell the client
};

// One Foxglove client text frame, validated (types, ranges, sizes, nesting).
FoxgloveRequest parse_foxglove_request(std::string_view text);
// One dashboard client text frame, validated likewise.
DashboardRequest parse_dashboard_request(std::string_view text);

// How many requests one client may make: `per_second` a second on average, bursts up to
// `burst`; the rest are refused (the server says so once per burst, not once per frame).
class RequestBudget {
 public:
  using Clock = std::chrono::steady_clock;
  RequestBudget(double per_second, double burst) : per_second_(per_second), burst_(burst), tokens_(burst) {}
  // Whether a request arriving at `now` may be served.
  bool take(Clock::time_point now);
  // True once after a refusal since the last served request: time to tell the client.
  bool refusal_to_report();

 private:
  double per_second_, burst_, tokens_;
  Clock::time_point last_{};
  bool started_ = false, refused_ = false, reported_ = false;
};

}  // namespace wysiwyf::bridge
