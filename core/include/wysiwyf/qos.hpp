#pragma once
// Quality of service of one port. A component declares defaults; the pipeline may override them.
#include <cstdint>
#include <string>

namespace wysiwyf {

enum class Reliability { kReliable, kBestEffort };
enum class Durability { kVolatile, kTransientLocal };

struct Qos {
  Reliability reliability = Reliability::kReliable;
  Durability durability = Durability::kVolatile;
  int depth = 4;                 // samples kept per reader (keep-last history)
  std::int64_t deadline_ns = 0;  // 0: none; else the longest expected gap between samples
  // A topic with one writer only (a robot's setpoint): on an input, a second output port on its
  // topic is a validation error; on an output, it declares itself that one writer. Between
  // processes such a topic has DDS exclusive ownership, and a reader follows one writer.
  bool single_writer = false;
  // An input the component works without (an alternative source, a cross-check): left
  // unconnected in a pipeline, it is not worth a warning (mapped to a topic nobody writes, it is).
  bool optional = false;

  static Qos reliable(int depth = 4) { return Qos{Reliability::kReliable, Durability::kVolatile, depth, 0}; }
  // Latest-value streams (images, sensor data): lose a sample rather than wait for it.
  static Qos sensor(int depth = 1) { return Qos{Reliability::kBestEffort, Durability::kVolatile, depth, 0}; }
  Qos one_writer() const {
    Qos q = *this;
    q.single_writer = true;
    return q;
  }
  Qos optional_input() const {
    Qos q = *this;
    q.optional = true;
    return q;
  }
};

std::string to_string(Reliability r);
std::string to_string(Durability d);

}  // namespace wysiwyf
