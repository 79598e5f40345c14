// wysiwyf topic list | echo TOPIC | hz TOPIC: watch the topics of running pipelines over DDS.
#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/domain/DomainParticipantListener.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>
#include <fastrtps/types/DynamicData.h>
#include <fastrtps/types/DynamicPubSubType.h>

#include <chrono>
#include <cmath>
#include <condition_variable>
#include <functional>
#include <iomanip>
#include <iostream>
#include <map>
#include <mutex>
#include <set>
#include <thread>

#include "cli.hpp"
#include "dds_session.hpp"
#include "dynamic_yaml.hpp"
#include "message_libraries.hpp"
#include "wysiwyf/dds.hpp"
#include "wysiwyf/msgs.hpp"
#include "wysiwyf/pipeline_spec.hpp"
#include "wysiwyf/runtime.hpp"

namespace wysiwyf::cli {

using namespace eprosima::fastdds::dds;
using Clock = std::chrono::steady_clock;

namespace {

using SamplePrinter = std::function<std::string(const void*)>;

double seconds_option(Args& args, const std::string& name, double fallback) {
  auto v = args.value(name);
  if (!v) return fallback;
  try {
    const double s = std::stod(*v);
    if (s >= 0 && std::isfinite(s)) return s;
  } catch (...) {
  }
  throw UsageError(name + ": found '" + *v + "'; expected a number of seconds");
}

long count_option(Args& args, const std::string& name) {
  auto v = args.value(name);
  if (!v) return 0;
  try {
    std::size_t used = 0;
    const long n = std::stol(*v, &used);
    if (used == v->size() && n >= 0) return n;
  } catch (...) {
  }
  throw UsageError(name + ": found '" + *v + "'; expected a whole number of samples (0: no limit)");
}

// Whether the reader still has a writer to hear from (after it had one): once every writer of
// the topic has gone, nothing more will come.
bool writers_gone(DataReader* reader) {
  SubscriptionMatchedStatus status;
  reader->get_subscription_matched_status(status);
  return status.total_count > 0 && status.current_count == 0;
}

// A reader on `topic` with the QoS of the writer found there, so that it matches, and how to
// print its samples: a type this build knows by its printer, any other from a message library.
DataReader* subscribe(Session& s, const std::string& topic, const TopicInfo& info, SamplePrinter& print) {
  TypeSupport support;
  if (const MessageType* type = msgs::registry().find(info.type)) {
    support.reset(type->make_type());
    print = type->to_yaml;
  } else {
    eprosima::fastrtps::types::DynamicType_ptr dynamic;
    std::string searched;
    if (!find_dynamic_type(info.type, dynamic, searched))
      throw std::runtime_error("topic '" + topic + "' carries " + info.type +
                               ", which neither this build nor a message library knows (searched " + searched + ")");
    support.reset(new eprosima::fastrtps::types::DynamicPubSubType(dynamic));
    print = [dynamic](const void* sample) {
      return dynamic_to_yaml(*static_cast<eprosima::fastrtps::types::DynamicData*>(const_cast<void*>(sample)), dynamic);
    };
  }
  support->auto_fill_type_object(false);  // as the pipelines' endpoints (core/src/dds_bridge.cpp)
  support->auto_fill_type_information(false);
  support.register_type(s.participant, info.type);
  Topic* t = s.participant->create_topic(topic, info.type, TOPIC_QOS_DEFAULT);
  Subscriber* sub = s.participant->create_subscriber(SUBSCRIBER_QOS_DEFAULT);
  Qos qos = Qos::reliable(100);
  qos.reliability = info.reliability == RELIABLE_RELIABILITY_QOS ? Reliability::kReliable : Reliability::kBestEffort;
  qos.durability = info.durability == VOLATILE_DURABILITY_QOS ? Durability::kVolatile : Durability::kTransientLocal;
  DataReader* reader = sub->create_datareader(t, dds::reader_qos(qos, info.keyed ? dds::kKeyedTopicInstances : 1));
  if (!reader) throw std::runtime_error("cannot create a reader on topic '" + topic + "'");
  return reader;
}

int topic_list(Args& args) {
  Session s;
  open(args, s);
  const double wait = seconds_option(args, "--wait", 2.0);
  if (!args.unknown_options().empty()) throw UsageError("unknown option " + args.unknown_options().front());
  std::this_thread::sleep_for(std::chrono::duration<double>(wait));
  const auto topics = s.discovery.topics();
  std::cout << std::left << std::setw(32) << "topic" << std::setw(40) << "type"
            << "writers readers\n";
  for (const auto& [name, t] : topics)
    std::cout << std::left << std::setw(32) << name << std::setw(40) << t.type << std::setw(8) << t.writers.size()
              << t.readers.size() << "\n";
  if (topics.empty()) std::cerr << "no topics seen in " << wait << " s\n";
  return 0;
}

int topic_echo(Args& args, const std::string& topic) {
  Session s;
  open(args, s);
  const long count = count_option(args, "--count");
  const double timeout = seconds_option(args, "--timeout", 10.0);
  if (!args.unknown_options().empty()) throw UsageError("unknown option " + args.unknown_options().front());
  install_stop_signal_handlers();
  const auto info = s.discovery.wait_for_writer(
      topic, Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(timeout)));
  if (!info) {
    std::cerr << "no writer on topic '" << topic << "' within " << timeout << " s\n";
    return 1;
  }
  SamplePrinter print;
  DataReader* reader = subscribe(s, topic, *info, print);
  std::cout << "# topic " << topic << " (" << info->type << ")\n" << std::flush;
  void* sample = reader->type()->createData();
  long printed = 0;
  // --timeout bounds the wait for the first sample; after it, echo runs until --count samples,
  // Ctrl-C, or the topic's last writer leaves.
  const auto deadline =
      Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(timeout));
  while (!stop_signal_received() && (count == 0 || printed < count)) {
    if (printed == 0 && Clock::now() > deadline) {
      std::cerr << "no sample on topic '" << topic << "' within " << timeout << " s\n";
      break;
    }
    if (!reader->wait_for_unread_message(eprosima::fastrtps::Duration_t(0, 100'000'000))) {
      if (writers_gone(reader)) {
        std::cerr << "every writer of topic '" << topic << "' has gone; " << printed << " sample(s) printed\n";
        break;
      }
      continue;
    }
    SampleInfo si;
    while (reader->take_next_sample(sample, &si) == ReturnCode_t::RETCODE_OK && (count == 0 || printed < count)) {
      if (!si.valid_data) continue;
      std::cout << "---\n" << print(sample) << std::flush;
      ++printed;
    }
  }
  reader->type()->deleteData(sample);
  return printed > 0 ? 0 : 1;
}

int topic_hz(Args& args, const std::string& topic) {
  Session s;
  open(args, s);
  const double window = seconds_option(args, "--window", 1.0);
  const double duration = seconds_option(args, "--duration", 0.0);
  const double timeout = seconds_option(args, "--timeout", 10.0);
  if (!args.unknown_options().empty()) throw UsageError("unknown option " + args.unknown_options().front());
  install_stop_signal_handlers();
  const auto info = s.discovery.wait_for_writer(
      topic, Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(timeout)));
  if (!info) {
    std::cerr << "no writer on topic '" << topic << "' within " << timeout << " s\n";
    return 1;
  }
  SamplePrinter print;
  DataReader* reader = subscribe(s, topic, *info, print);
  void* sample = reader->type()->createData();
  const auto start = Clock::now();
  auto window_end = start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(window));
  std::vector<double> gaps;
  std::optional<Clock::time_point> last;
  std::uint64_t total = 0;
  while (!stop_signal_received()) {
    if (duration > 0 && Clock::now() - start >= std::chrono::duration<double>(duration)) break;
    if (writers_gone(reader) && reader->get_unread_count() == 0) {
      std::cerr << "every writer of topic '" << topic << "' has gone\n";
      break;
    }
    if (reader->wait_for_unread_message(eprosima::fastrtps::Duration_t(0, 20'000'000))) {
      SampleInfo si;
      while (reader->take_next_sample(sample, &si) == ReturnCode_t::RETCODE_OK) {
        if (!si.valid_data) continue;
        const auto now = Clock::now();
        if (last) gaps.push_back(std::chrono::duration<double>(now - *last).count());
        last = now;
        ++total;
      }
    }
    if (Clock::now() >= window_end) {
      if (gaps.empty()) {
        std::cout << "no new samples\n";
      } else {
        double sum = 0, sq = 0, lo = gaps[0], hi = gaps[0];
        for (double g : gaps) sum += g, sq += g * g, lo = std::min(lo, g), hi = std::max(hi, g);
        const double mean = sum / gaps.size();
        const double sd = std::sqrt(std::max(0.0, sq / gaps.size() - mean * mean));
        std::cout << std::fixed << std::setprecision(3) << "rate " << 1.0 / mean << " Hz  min " << lo * 1e3
                  << " ms  max " << hi * 1e3 << " ms  std " << sd * 1e3 << " ms  n " << gaps.size() + 1 << "\n"
                  << std::flush;
      }
      gaps.clear();
      window_end += std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(window));
    }
  }
  reader->type()->deleteData(sample);
  return total > 0 ? 0 : 1;
}

}  // namespace

int cmd_topic(Args args) {
  const auto sub = args.take_front().value_or("");
  const auto topic = sub == "list" ? std::optional<std::string>("") : args.take_front();
  if (!topic) throw UsageError("topic " + sub + ": expected a topic name");
  if (sub == "list") return topic_list(args);
  if (sub == "echo") return topic_echo(args, *topic);
  if (sub == "hz") return topic_hz(args, *topic);
  throw UsageError("expected 'topic list', 'topic echo TOPIC' or 'topic hz TOPIC'");
}

}  // namespace wysiwyf::cli
