#pragma once
// Who publishes and who subscribes each topic of the domain, as the Foxglove protocol's
// `connectionGraph` capability tells it (its Topic Graph panel): participants by the names they
// announce. The server sends a client the whole graph when it subscribes, then what changed.
#include <map>
#include <set>
#include <string>

namespace wysiwyf::bridge {

struct ConnectionGraph {
  std::map<std::string, std::set<std::string>> published;   // topic -> publisher ids
  std::map<std::string, std::set<std::string>> subscribed;  // topic -> subscriber ids
  bool operator==(const ConnectionGraph& o) const { return published == o.published && subscribed == o.subscribed; }
};

// The connectionGraphUpdate message that takes a client from `before` to `now` (from an empty
// graph: the whole of it), or "" when nothing changed.
std::string connection_graph_update(const ConnectionGraph& before, const ConnectionGraph& now);

}  // namespace wysiwyf::bridge
