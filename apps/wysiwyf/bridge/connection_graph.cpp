#include "connection_graph.hpp"

#include <nlohmann/json.hpp>

namespace wysiwyf::bridge {

using json = nlohmann::json;

namespace {

// Topics whose ids changed or appeared, as [{name, <ids_key>: [...]}, ...].
json changed(const std::map<std::string, std::set<std::string>>& before,
             const std::map<std::string, std::set<std::string>>& now, const char* ids_key) {
  json out = json::array();
  for (const auto& [topic, ids] : now) {
    const auto was = before.find(topic);
    if (was == before.end() || was->second != ids) out.push_back({{"name", topic}, {ids_key, ids}});
  }
  return out;
}

}  // namespace

std::string connection_graph_update(const ConnectionGraph& before, const ConnectionGraph& now) {
  if (before == now) return "";
  // A topic is removed when nobody publishes or subscribes it any more.
  json removed = json::array();
  const auto known = [&](const std::string& topic) {
    return now.published.count(topic) || now.subscribed.count(topic);
  };
  std::set<std::string> gone;
  for (const auto* side : {&before.published, &before.subscribed})
    for (const auto& [topic, ids] : *side)
      if (!known(topic)) gone.insert(topic);
  for (const auto& topic : gone) removed.push_back(topic);
  const json update{{"op", "connectionGraphUpdate"},
                    {"publishedTopics", changed(before.published, now.published, "publisherIds")},
                    {"subscribedTopics", changed(before.subscribed, now.subscribed, "subscriberIds")},
                    {"advertisedServices", json::array()},
                    {"removedTopics", removed},
                    {"removedServices", json::array()}};
  return update.dump(-1, ' ', false, json::error_handler_t::replace);
}

}  // namespace wysiwyf::bridge
