#include "client_requests.hpp"

#include <algorithm>
#include <limits>
#include <nlohmann/json.hpp>

namespace wysiwyf::bridge {

using json = nlohmann::json;

namespace {

// The first bytes of a client's text, printable ASCII only, for a message that quotes it.
std::string excerpt(std::string_view text) {
  std::string out;
  for (const char c : text.substr(0, 60)) out += (c >= 0x20 && c < 0x7f) ? c : '?';
  return "'" + out + (text.size() > 60 ? "...'" : "'");
}

// How deep arrays and objects nest in `text`, strings skipped; stops counting past `limit`, so
// a frame of 200,000 brackets costs one pass and no recursion.
int nesting_depth(std::string_view text, int limit) {
  int depth = 0, deepest = 0;
  bool in_string = false, escaped = false;
  for (const char c : text) {
    if (in_string) {
      if (escaped)
        escaped = false;
      else if (c == '\\')
        escaped = true;
      else if (c == '"')
        in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      deepest = std::max(deepest, ++depth);
      if (deepest > limit) return deepest;
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return deepest;
}

const char* kind(const json& v) {
  switch (v.type()) {
    case json::value_t::null: return "null";
    case json::value_t::boolean: return "a boolean";
    case json::value_t::string: return "a string";
    case json::value_t::array: return "an array";
    case json::value_t::object: return "an object";
    case json::value_t::number_float: return "a fraction";
    case json::value_t::number_integer: return v.get<std::int64_t>() < 0 ? "a negative number" : "a number";
    case json::value_t::number_unsigned:
      return v.get<std::uint64_t>() > std::numeric_limits<std::uint32_t>::max() ? "a number over 4294967295"
                                                                                : "a number";
    default: return "something else";
  }
}

// A uint32 from `v`, or why not.
bool to_u32(const json& v, std::uint32_t& out) {
  if (v.is_number_unsigned() || (v.is_number_integer() && v.get<std::int64_t>() >= 0)) {
    const auto n = v.get<std::uint64_t>();
    if (n <= std::numeric_limits<std::uint32_t>::max()) {
      out = static_cast<std::uint32_t>(n);
      return true;
    }
  }
  return false;
}

// The JSON object of a request with its string "op", or a problem.
bool parse_object(std::string_view text, json& m, std::string& problem) {
  if (text.size() > kMaxRequestBytes) {
    problem = "a request of " + std::to_string(text.size()) + " bytes; at most " + std::to_string(kMaxRequestBytes);
    return false;
  }
  if (nesting_depth(text, kMaxRequestDepth) > kMaxRequestDepth) {
    problem = "a request nested deeper than " + std::to_string(kMaxRequestDepth) + " arrays or objects";
    return false;
  }
  m = json::parse(text.begin(), text.end(), nullptr, false);
  if (m.is_discarded() || !m.is_object()) {
    problem = "expected a JSON object with an \"op\"; got " + excerpt(text);
    return false;
  }
  const auto op = m.find("op");
  if (op == m.end() || !op->is_string()) {
    problem = std::string("expected \"op\" to be a string; got ") + (op == m.end() ? "none" : kind(*op));
    return false;
  }
  return true;
}

void parse_subscribe(const json& m, FoxgloveRequest& r) {
  const auto subs = m.find("subscriptions");
  if (subs == m.end() || !subs->is_array()) {
    r.problem = std::string("subscribe: expected \"subscriptions\" to be an array; got ") +
                (subs == m.end() ? "none" : kind(*subs));
    return;
  }
  if (subs->size() > kMaxSubscriptionsPerRequest) {
    r.problem = "subscribe: " + std::to_string(subs->size()) + " subscriptions in one request; at most " +
                std::to_string(kMaxSubscriptionsPerRequest);
    return;
  }
  for (std::size_t i = 0; i < subs->size(); ++i) {
    const json& s = (*subs)[i];
    const std::string where = "subscribe: subscriptions[" + std::to_string(i) + "]";
    if (!s.is_object()) {
      r.problem = where + ": expected an object {\"id\", \"channelId\"}; got " + kind(s);
      return;
    }
    Subscription sub;
    for (const auto& [key, field] : {std::pair{"id", &sub.id}, std::pair{"channelId", &sub.channel}}) {
      const auto v = s.find(key);
      if (v == s.end() || !to_u32(*v, *field)) {
        r.problem = where + "." + key + ": expected a whole number from 0 to 4294967295; got " +
                    (v == s.end() ? "none" : kind(*v));
        return;
      }
    }
    r.subscriptions.push_back(sub);
  }
  r.op = FoxgloveRequest::Op::kSubscribe;
}

void parse_unsubscribe(const json& m, FoxgloveRequest& r) {
  const auto ids = m.find("subscriptionIds");
  if (ids == m.end() || !ids->is_array()) {
    r.problem = std::string("unsubscribe: expected \"subscriptionIds\" to be an array; got ") +
                (ids == m.end() ? "none" : kind(*ids));
    return;
  }
  if (ids->size() > kMaxSubscriptionsPerRequest) {
    r.problem = "unsubscribe: " + std::to_string(ids->size()) + " ids in one request; at most " +
                std::to_string(kMaxSubscriptionsPerRequest);
    return;
  }
  for (std::size_t i = 0; i < ids->size(); ++i) {
    std::uint32_t id = 0;
    if (!to_u32((*ids)[i], id)) {
      r.problem = "unsubscribe: subscriptionIds[" + std::to_string(i) +
                  "]: expected a whole number from 0 to 4294967295; got " + kind((*ids)[i]);
      r.unsubscribe.clear();
      return;
    }
    r.unsubscribe.push_back(id);
  }
  r.op = FoxgloveRequest::Op::kUnsubscribe;
}

// A dashboard's topic or field: a non-empty printable name of bounded size.
bool name_field(const json& m, const char* key, std::string& out, std::string& problem, const std::string& op) {
  const auto v = m.find(key);
  if (v == m.end() || !v->is_string()) {
    problem = op + ": expected \"" + key + "\" to be a string; got " + (v == m.end() ? "none" : kind(*v));
    return false;
  }
  const auto& s = v->get_ref<const std::string&>();
  const bool printable = std::all_of(s.begin(), s.end(), [](char c) { return c >= 0x20 && c < 0x7f; });
  if (s.empty() || s.size() > kMaxNameBytes || !printable) {
    problem = op + ": \"" + key + "\" must be 1 to " + std::to_string(kMaxNameBytes) +
              " printable ASCII characters; got " + excerpt(s);
    return false;
  }
  out = s;
  return true;
}

}  // namespace

FoxgloveRequest parse_foxglove_request(std::string_view text) {
  FoxgloveRequest r;
  json m;
  if (!parse_object(text, m, r.problem)) return r;
  const auto& op = m["op"].get_ref<const std::string&>();
  if (op == "subscribe") {
    parse_subscribe(m, r);
  } else if (op == "unsubscribe") {
    parse_unsubscribe(m, r);
  } else if (op == "subscribeConnectionGraph") {
    r.op = FoxgloveRequest::Op::kSubscribeGraph;
  } else if (op == "unsubscribeConnectionGraph") {
    r.op = FoxgloveRequest::Op::kUnsubscribeGraph;
  } else {
    r.op = FoxgloveRequest::Op::kUnsupported;
    r.problem = "op " + excerpt(op) +
                " is not supported by this server (it streams: subscribe, unsubscribe, subscribeConnectionGraph, "
                "unsubscribeConnectionGraph)";
  }
  return r;
}

DashboardRequest parse_dashboard_request(std::string_view text) {
  DashboardRequest r;
  json m;
  if (!parse_object(text, m, r.problem)) return r;
  const auto& op = m["op"].get_ref<const std::string&>();
  if (op != "plot" && op != "unplot") {
    r.problem = "op " + excerpt(op) + " is not a dashboard request (expected plot or unplot)";
    return r;
  }
  if (name_field(m, "topic", r.topic, r.problem, op) && name_field(m, "field", r.field, r.problem, op))
    r.op = op == "plot" ? DashboardRequest::Op::kPlot : DashboardRequest::Op::kUnplot;
  return r;
}

bool RequestBudget::take(Clock::time_point now) {
  if (started_) {
    const double elapsed = std::chrono::duration<double>(now - last_).count();
    tokens_ = std::min(burst_, tokens_ + std::max(0.0, elapsed) * per_second_);
  }
  started_ = true;
  last_ = now;
  if (tokens_ >= 1.0) {
    tokens_ -= 1.0;
    refused_ = reported_ = false;
    return true;
  }
  refused_ = true;
  return false;
}

bool RequestBudget::refusal_to_report() {
  if (!refused_ || reported_) return false;
  reported_ = true;
  return true;
}

}  // namespace wysiwyf::bridge
