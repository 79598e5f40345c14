#pragma once
/// @file
/// What a component sees while it configures: its parameters and ports. The same configure() runs
/// in three modes: describe (no pipeline: defaults, for `components describe`), validate (the
/// pipeline's values are checked, nothing is connected) and run (ports connected to topics).
/// configure() must therefore only declare and read: open devices and threads in activate().
#include <algorithm>
#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "wysiwyf/detail/topic_bus.hpp"
#include "wysiwyf/location.hpp"
#include "wysiwyf/params.hpp"
#include "wysiwyf/port.hpp"
#include "wysiwyf/time.hpp"

namespace wysiwyf {

struct ComponentSpec;  // the pipeline's entry for this component (pipeline_spec.hpp)

namespace detail {
struct ContextAccess;
template <class T>
struct IsStdArray : std::false_type {};
template <class V, std::size_t N>
struct IsStdArray<std::array<V, N>> : std::true_type {};
}  // namespace detail

/// What a component sees while it configures: it declares and reads its parameters, declares its
/// ports and says what it does. The same configure() runs in three modes (Mode); it must only
/// declare and read: open devices and threads in activate().
class Context {
 public:
  /// Which of the three runs of configure() this is.
  enum class Mode {
    kDescribe,  ///< no pipeline: defaults, for `components describe`
    kValidate,  ///< the pipeline's values are checked, nothing is connected
    kRun        ///< ports connected to topics
  };

  /// spec is null in describe mode; bus is non-null only in run mode.
  Context(Mode mode, const ComponentSpec* spec, detail::TopicBus* bus);

  /// A parameter: the pipeline's value, or default_value when the pipeline gives none. T is bool,
  /// int, int64_t, double, std::string, `std::vector<double>`, `std::vector<std::string>`, or
  /// `std::array<double, N>` (a list of exactly N). `range` bounds numbers (each element of a
  /// list); `length` says how many elements a list may have. A wrong value is reported at its
  /// file:line:column and the default is returned.
  template <class T>
  T param(const std::string& name, const T& default_value, const std::string& description,
          std::optional<Range> range = std::nullopt, std::optional<Length> length = std::nullopt);
  /// A string parameter that must be one of `choices`.
  std::string param_choice(const std::string& name, const std::string& default_value, const std::string& description,
                           const std::vector<std::string>& choices);

  /// Refuses the value of parameter `name` (declared before) for a reason the declaration cannot
  /// express, such as a relation between two parameters: reported like a wrong type or range, at
  /// the value's file:line:column ("parameter 'outer' of component 'keyer' (chroma_keyer): must be
  /// larger than inner (22)"). configure() goes on; the pipeline does not start.
  void reject(const std::string& name, const std::string& why);

  /// An input port receiving T. `qos` is the component's default; the pipeline may override it
  /// per port.
  template <class T>
  Input<T> input(const std::string& port, const std::string& description, Qos qos = Qos::reliable());
  /// An output port publishing T. `qos` is the component's default; the pipeline may override it
  /// per port.
  template <class T>
  Output<T> output(const std::string& port, const std::string& description, Qos qos = Qos::reliable());

  /// One line saying what the component does, for `wysiwyf components list`.
  void summary(std::string text) { summary_ = std::move(text); }

  /// Which run of configure() this is: describe, validate or run.
  Mode mode() const { return mode_; }
  /// The instance's name in the pipeline.
  const std::string& instance_name() const { return instance_; }
  double rate_hz() const;  ///< the rate the pipeline ticks this component at
  /// The tick period in nanoseconds (1 / rate_hz(), rounded); 0 when the pipeline gives no rate.
  std::int64_t period_ns() const;

  /// What was wrong so far (reject(), wrong values): configure() may skip work when not empty.
  const std::vector<ConfigIssue>& issues() const { return issues_; }

 private:
  friend struct detail::ContextAccess;  // the kernel reads what was declared (core/internal)
  // One per parameter type: declare, look up, convert, check range and length (context.cpp).
  bool read(const std::string& name, const bool& default_value, const std::string& description,
            std::optional<Range> range, std::optional<Length> length, bool& out);
  bool read(const std::string& name, const int& default_value, const std::string& description,
            std::optional<Range> range, std::optional<Length> length, int& out);
  bool read(const std::string& name, const std::int64_t& default_value, const std::string& description,
            std::optional<Range> range, std::optional<Length> length, std::int64_t& out);
  bool read(const std::string& name, const double& default_value, const std::string& description,
            std::optional<Range> range, std::optional<Length> length, double& out);
  bool read(const std::string& name, const std::string& default_value, const std::string& description,
            std::optional<Range> range, std::optional<Length> length, std::string& out);
  bool read(const std::string& name, const std::vector<double>& default_value, const std::string& description,
            std::optional<Range> range, std::optional<Length> length, std::vector<double>& out);
  bool read(const std::string& name, const std::vector<std::string>& default_value, const std::string& description,
            std::optional<Range> range, std::optional<Length> length, std::vector<std::string>& out);
  template <class T>
  bool read_as(const std::string& name, const T& default_value, const std::string& description,
               std::optional<Range> range, std::optional<Length> length, T& out);

  void declare_param(ParamSpec spec);
  void declare_port(PortSpec spec);
  void add_issue(const Location& where, std::string message);
  Location param_location(const std::string& name) const;
  std::string param_label(const std::string& name) const;
  Qos effective_qos(const std::string& port, Qos declared) const;
  std::string topic_for(const std::string& port) const;

  Mode mode_;
  const ComponentSpec* spec_;
  detail::TopicBus* bus_;
  std::string instance_;
  std::string summary_;
  std::vector<ParamSpec> params_;
  std::vector<PortSpec> ports_;
  std::vector<ConfigIssue> issues_;
  std::vector<const detail::QueueCounters*> input_queues_;
  std::map<std::string, detail::QueueCounters*> input_by_port_;
};

template <class T>
T Context::param(const std::string& name, const T& default_value, const std::string& description,
                 std::optional<Range> range, std::optional<Length> length) {
  if constexpr (detail::IsStdArray<T>::value) {
    static_assert(std::is_same_v<typename T::value_type, double>, "fixed-size parameters are std::array<double, N>");
    const std::vector<double> list =
        param<std::vector<double>>(name, std::vector<double>(default_value.begin(), default_value.end()), description,
                                   range, Length::exactly(std::tuple_size<T>::value));
    T out = default_value;
    if (list.size() == out.size()) std::copy(list.begin(), list.end(), out.begin());
    return out;
  } else {
    T value = default_value;
    if (!read(name, default_value, description, range, length, value)) return default_value;
    return value;
  }
}

template <class T>
Input<T> Context::input(const std::string& port, const std::string& description, Qos qos) {
  const Qos effective = effective_qos(port, qos);
  declare_port(PortSpec{port, PortDirection::kInput, MessageTraits<T>::type_name(), description, qos});
  if (!bus_) return Input<T>();
  auto* queue = bus_->channel<T>(topic_for(port), instance_ + "." + port)->add_reader(effective);
  input_queues_.push_back(queue);
  input_by_port_[port] = queue;
  return Input<T>(queue, port);
}

template <class T>
Output<T> Context::output(const std::string& port, const std::string& description, Qos qos) {
  const Qos effective = effective_qos(port, qos);
  declare_port(PortSpec{port, PortDirection::kOutput, MessageTraits<T>::type_name(), description, qos});
  if (!bus_) return Output<T>();
  auto* channel = bus_->channel<T>(topic_for(port), instance_ + "." + port);
  channel->add_writer(effective);
  return Output<T>(channel);
}

}  // namespace wysiwyf
