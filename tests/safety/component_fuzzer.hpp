#pragma once
// A structured fuzzer of one component's inputs, through the Harness: seeded sequences of ticks,
// each feeding every declared input random samples of its type (random_sample.hpp: plausible and
// hostile ones mixed) at a sim clock that only moves forward, now by one period, now by many. What
// the component writes is checked after every tick:
//  - it does not throw (a component's tick that throws stops a pipeline);
//  - every number of every output sample is finite;
//  - a Cartesian setpoint's orientation is a unit quaternion (where it is out of the arm's reach,
//    the arm's safety gate refuses it: safety_gate.hpp);
//  - the port's own check (FuzzOptions::check), if any.
// Every so many sequences the component is made again (configure, activate), so its start meets
// the inputs too. The seed and the sequence's index replay a finding.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "wysiwyf/harness.hpp"

namespace wysiwyf::safety {

struct FuzzOptions {
  std::string type;           // the component type
  std::string params = "{}";  // its parameters (YAML)
  double rate_hz = 1000;      // its tick rate: one period between most ticks
  std::uint64_t sequences = 1000;
  std::uint64_t seed = 1;
  int ticks_per_sequence = 20;  // at most
  int restart_every = 500;      // sequences between fresh instances
  // Called with each output sample's port and CDR bytes: a finding's text, or empty.
  std::function<std::string(const std::string& port, const std::vector<std::uint8_t>& cdr)> check;
};

struct FuzzResult {
  std::uint64_t sequences = 0, ticks = 0;
  std::uint64_t fed = 0;                       // samples the component received
  std::uint64_t refused_by_dds = 0;            // generated samples deserialisation refused (over a bound)
  std::uint64_t rejected = 0;                  // samples the component rejected (Component::reject)
  std::uint64_t outputs = 0;                   // samples it wrote, all checked
  std::vector<std::string> inputs, unwatched;  // input ports; output ports of types without a description
  std::vector<std::string> findings;           // each with its sequence index (at most 20 kept)
  std::uint64_t finding_count = 0;
  double slowest_tick_s = 0;
};

// Throws std::runtime_error when the component cannot be made with these params, or has an
// input of a type the fuzzer has no description of.
FuzzResult fuzz_component(const FuzzOptions& options, Loader& loader);

}  // namespace wysiwyf::safety
