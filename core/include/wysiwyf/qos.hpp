#pragma once
/// @file
/// Quality of service of one port. A component declares defaults; the pipeline may override them.
#include <cstdint>
#include <string>

namespace wysiwyf {

/// Whether a lost sample is sent again (between processes, over DDS).
enum class Reliability {
  kReliable,   ///< lost samples are sent again; for commands and events
  kBestEffort  ///< a late sample is dropped rather than waited for; for latest-value streams
};
/// Whether a reader that joins late gets samples written before it joined.
enum class Durability {
  kVolatile,       ///< a reader gets only what is written after it joined
  kTransientLocal  ///< a late reader gets the writer's last samples too (up to the depth)
};

/// Quality of service of one port. A component declares defaults; the pipeline may override them.
struct Qos {
  Reliability reliability = Reliability::kReliable;  ///< whether lost samples are sent again
  Durability durability = Durability::kVolatile;     ///< whether a late reader gets earlier samples
  int depth = 4;                                     ///< samples kept per reader (keep-last history)
  std::int64_t deadline_ns = 0;                      ///< 0: none; else the longest expected gap between samples
  /// A topic with one writer only (a robot's setpoint): on an input, a second output port on its
  /// topic is a validation error; on an output, it declares itself that one writer. Between
  /// processes such a topic has DDS exclusive ownership, and a reader follows one writer.
  bool single_writer = false;
  /// An input the component works without (an alternative source, a cross-check): left
  /// unconnected in a pipeline, it is not worth a warning (mapped to a topic nobody writes, it is).
  bool optional = false;

  /// Reliable and volatile, keeping `depth` samples per reader: for commands and events, and for
  /// streams where every sample counts.
  static Qos reliable(int depth = 4) { return Qos{Reliability::kReliable, Durability::kVolatile, depth, 0}; }
  /// Latest-value streams (images, sensor data): lose a sample rather than wait for it.
  static Qos sensor(int depth = 1) { return Qos{Reliability::kBestEffort, Durability::kVolatile, depth, 0}; }
  /// This QoS with single_writer set: the topic has one writer only.
  Qos one_writer() const {
    Qos q = *this;
    q.single_writer = true;
    return q;
  }
  /// This QoS with optional set: an input the component works without.
  Qos optional_input() const {
    Qos q = *this;
    q.optional = true;
    return q;
  }
};

/// The reliability's name as pipelines write it: "reliable" or "best_effort".
std::string to_string(Reliability r);
/// The durability's name as pipelines write it: "volatile" or "transient_local".
std::string to_string(Durability d);

}  // namespace wysiwyf
