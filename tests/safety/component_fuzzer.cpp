#include "component_fuzzer.hpp"

#include <fastdds/dds/topic/TopicDataType.hpp>
#include <fastrtps/types/TypeObjectFactory.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <iostream>
#include <memory>
#include <stdexcept>

#include "finite_check.hpp"
#include "random_sample.hpp"
#include "wysiwyf/kernel_msgs.hpp"
#include "wysiwyf/msgs.hpp"

namespace wysiwyf::safety {

namespace {

using eprosima::fastrtps::rtps::SerializedPayload_t;
using Bytes = std::vector<std::uint8_t>;

types::DynamicType_ptr dynamic_type(const std::string& name) {
  msgs::register_type_objects();
  auto* factory = types::TypeObjectFactory::get_instance();
  const types::TypeIdentifier* id = factory->get_type_identifier(name, true);
  const types::TypeObject* object = factory->get_type_object(name, true);
  types::DynamicType_ptr type;
  if (id && object) type = factory->build_dynamic_type(name, id, object);
  return type;
}

// One input port: CDR bytes in, the component's sample written (as a DDS reader would deliver it).
struct PortFeed {
  virtual ~PortFeed() = default;
  virtual bool feed(const Bytes& cdr) = 0;  // false: deserialisation refused the bytes
  types::DynamicType_ptr type;
};

template <class T>
struct TypedFeed final : PortFeed {
  TypedFeed(Harness& h, const std::string& port) : out(h.feed<T>(port)), support(MessageTraits<T>::make_type()) {}
  bool feed(const Bytes& cdr) override {
    SerializedPayload_t payload(static_cast<std::uint32_t>(cdr.size()));
    std::memcpy(payload.data, cdr.data(), cdr.size());
    payload.length = static_cast<std::uint32_t>(cdr.size());
    T sample;
    if (!support->deserialize(&payload, &sample)) return false;
    out.write(sample);
    return true;
  }
  Output<T> out;
  std::unique_ptr<eprosima::fastdds::dds::TopicDataType> support;
};

// What a sample of its type must also hold beyond finite numbers: "" for most types.
template <class T>
std::string typed_problem(const T&) {
  return "";
}
// A setpoint's orientation is a unit quaternion.
std::string typed_problem(const msg::CartesianSetpoint& s) {
  const auto& q = s.pose().orientation();
  const double norm = std::sqrt(q.x() * q.x() + q.y() * q.y() + q.z() * q.z() + q.w() * q.w());
  return std::abs(norm - 1) > 1e-6 ? "a setpoint's quaternion of length " + std::to_string(norm) : "";
}

// One output port: every sample the component wrote, as CDR bytes, and what its type's own
// check (typed_problem) found in it.
struct PortWatch {
  virtual ~PortWatch() = default;
  virtual bool next(Bytes& cdr, std::string& problem) = 0;
  types::DynamicType_ptr type;
  std::string port;
};

template <class T>
struct TypedWatch final : PortWatch {
  TypedWatch(Harness& h, const std::string& p) : in(h.watch<T>(p)), support(MessageTraits<T>::make_type()) {}
  bool next(Bytes& cdr, std::string& problem) override {
    T sample;
    if (!in.take(sample)) return false;
    SerializedPayload_t payload(support->getSerializedSizeProvider(&sample)());
    if (!support->serialize(&sample, &payload)) throw std::runtime_error("an output sample does not serialise");
    cdr.assign(payload.data, payload.data + payload.length);
    problem = typed_problem(sample);
    return true;
  }
  Input<T> in;
  std::unique_ptr<eprosima::fastdds::dds::TopicDataType> support;
};

template <class... Ts>
struct Messages {
  static std::unique_ptr<PortFeed> feed(Harness& h, const PortSpec& p) {
    std::unique_ptr<PortFeed> r;
    ((p.type_name == MessageTraits<Ts>::type_name() ? (void)(r = std::make_unique<TypedFeed<Ts>>(h, p.name)) : (void)0),
     ...);
    return r;
  }
  static std::unique_ptr<PortWatch> watch(Harness& h, const PortSpec& p) {
    std::unique_ptr<PortWatch> r;
    ((p.type_name == MessageTraits<Ts>::type_name() ? (void)(r = std::make_unique<TypedWatch<Ts>>(h, p.name))
                                                    : (void)0),
     ...);
    return r;
  }
};
using AllMessages =
    Messages<msg::Image, msg::CameraInfo, msg::JointState, msg::PoseStamped, msg::PoseWithCovariance,
             msg::WrenchStamped, msg::CartesianSetpoint, msg::ObjectState, msg::DisplayMode, msg::RobotStatus,
             msg::ArmRequest, msg::MarkerObservation, msg::HandPosition, msg::Attachment, msg::PlannerStatus,
             msg::UserEvent, msg::ContactReport, msg::HapticRegistration, kernel_msgs::Diagnostics>;

struct Instance {
  Instance(const FuzzOptions& o, Loader& loader) : h(o.type, o.params, o.rate_hz, &loader) {
    for (const PortSpec& p : h.description().ports) {
      if (p.direction == PortDirection::kInput) {
        auto f = AllMessages::feed(h, p);
        if (!f) throw std::runtime_error(o.type + "." + p.name + ": no fuzzer for its type " + p.type_name);
        f->type = dynamic_type(p.type_name);
        if (!f->type) throw std::runtime_error(p.type_name + ": no type object to generate samples from");
        inputs.push_back(std::move(f));
        names.push_back(p.name);
      } else if (auto w = AllMessages::watch(h, p); w && (w->type = dynamic_type(p.type_name))) {
        w->port = p.name;
        outputs.push_back(std::move(w));
      } else {
        unwatched.push_back(p.name + " (" + p.type_name + ")");
      }
    }
    h.activate();
  }
  Harness h;
  std::vector<std::unique_ptr<PortFeed>> inputs;
  std::vector<std::unique_ptr<PortWatch>> outputs;
  std::vector<std::string> names, unwatched;
};

// The Harness says every distinct rejection on std::cerr: thousands of lines of random text here
// (the counts are in the result).
struct QuietHarness {
  QuietHarness() : said(std::cerr.rdbuf(nullptr)) {}
  ~QuietHarness() {
    std::cerr.rdbuf(said);
    std::cerr.clear();
  }
  std::streambuf* said;
};

}  // namespace

FuzzResult fuzz_component(const FuzzOptions& o, Loader& loader) {
  const QuietHarness quiet;
  FuzzResult r;
  RandomSample random(o.seed);
  auto& rng = random.rng();
  const auto period = static_cast<std::int64_t>(1e9 / o.rate_hz);
  std::int64_t now = 0;
  std::unique_ptr<Instance> c;
  const auto find = [&](std::uint64_t sequence, const std::string& what) {
    if (r.findings.size() < 20) r.findings.push_back("sequence " + std::to_string(sequence) + ": " + what);
    ++r.finding_count;
  };
  for (std::uint64_t s = 0; s < o.sequences; ++s) {
    if (!c || s % static_cast<std::uint64_t>(o.restart_every) == 0) {
      if (c)
        r.rejected += [&] {
          std::uint64_t n = 0;
          for (const auto& name : c->names) n += c->h.rejected(name);
          return n;
        }();
      c.reset();
      c = std::make_unique<Instance>(o, loader);
      if (r.inputs.empty()) r.inputs = c->names, r.unwatched = c->unwatched;
      now = 0;
    }
    const double hostility = std::uniform_int_distribution<int>(0, 1)(rng) ? 0.3 : 0.0;
    const int ticks = 1 + std::uniform_int_distribution<int>(0, o.ticks_per_sequence - 1)(rng);
    for (int t = 0; t < ticks; ++t) {
      const int u = std::uniform_int_distribution<int>(0, 99)(rng);
      now += u < 90 ? period : u < 98 ? period * (2 + u % 8) : period * 1000;  // on time, late, a second late
      for (const auto& in : c->inputs) {
        const int k = std::uniform_int_distribution<int>(0, 9)(rng);
        const int n = k < 4 ? 0 : k < 9 ? 1 : 3;
        for (int i = 0; i < n; ++i) {
          const bool hostile = std::uniform_real_distribution<double>(0, 1)(rng) < hostility;
          if (in->feed(random.make(in->type, now, hostile)))
            ++r.fed;
          else
            ++r.refused_by_dds;
        }
      }
      const auto start = std::chrono::steady_clock::now();
      try {
        c->h.tick(Time{now});
      } catch (const std::exception& e) {
        find(s, std::string("tick threw: ") + e.what());
      }
      r.slowest_tick_s =
          std::max(r.slowest_tick_s, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      ++r.ticks;
      Bytes cdr;
      std::string typed;
      for (const auto& out : c->outputs)
        while (out->next(cdr, typed)) {
          ++r.outputs;
          std::string problem = FiniteCheck::first_non_finite(cdr, out->type);
          if (problem.empty()) problem = typed;
          if (problem.empty() && o.check) problem = o.check(out->port, cdr);
          if (!problem.empty()) find(s, out->port + ": " + problem);
        }
    }
    ++r.sequences;
  }
  if (c)
    for (const auto& name : c->names) r.rejected += c->h.rejected(name);
  return r;
}

}  // namespace wysiwyf::safety
