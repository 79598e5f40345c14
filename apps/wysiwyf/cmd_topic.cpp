// wysiwyf topic list | echo TOPIC | hz TOPIC: watch the topics of running pipelines over DDS.
#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/domain/DomainParticipantListener.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastrtps/types/DynamicTypePtr.h>
#include <fastdds/dds/subscriber/Subscriber.hpp>

#include <algorithm>
#include <limits>
#include <atomic>
#include <chrono>
#include <cstring>
#include <cmath>
#include <condition_variable>
#include <functional>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <sstream>
#include <thread>

#include "cli.hpp"
#include "dds_session.hpp"
#include "yaml_field.hpp"
#include "cdr_yaml.hpp"
#include "idl_schemas.hpp"
#include "raw_cdr_type.hpp"
#include "message_libraries.hpp"
#include "wysiwyf/dds.hpp"
#include "wysiwyf/pipeline_spec.hpp"
#include "wysiwyf/runtime.hpp"
#include "wysiwyf/validator.hpp"

namespace wysiwyf::cli {

using namespace eprosima::fastdds::dds;
using Clock = std::chrono::steady_clock;

namespace {

using SamplePrinter = std::function<std::string(const RawCdr&)>;

double seconds_option(Args& args, const std::string& name, double fallback) {
  return number_option(args, name, fallback, 0, std::numeric_limits<double>::infinity(), "a number of seconds");
}

long count_option(Args& args, const std::string& name) {
  return whole_option(args, name, 0, 0, std::numeric_limits<long>::max(), "a whole number of samples (0: no limit)");
}

// Why no writer was found for `topic`: where the tool looked, and the topics there that come
// closest to the name (a typo, a missing prefix).
std::string no_writer_message(const Session& s, const std::string& topic, double timeout,
                              const std::map<std::string, TopicInfo>& topics) {
  std::ostringstream out;
  out << "no writer on topic '" << topic << "' in DDS domain " << s.domain << " (transport " << s.transport
      << ") within " << timeout << " s";
  // The closest name (a typo), then names that contain it or that it contains (a missing prefix).
  std::vector<std::string> written, close;
  for (const auto& [name, info] : topics)
    if (!info.writers.empty()) written.push_back(name);
  if (const std::string nearest = closest_name(topic, written); !nearest.empty()) close.push_back(nearest);
  for (const auto& name : written)
    if ((name.find(topic) != std::string::npos || topic.find(name) != std::string::npos) &&
        std::find(close.begin(), close.end(), name) == close.end())
      close.push_back(name);
  const std::size_t with_writers = written.size();
  if (!close.empty()) {
    out << "; did you mean";
    for (std::size_t i = 0; i < close.size() && i < 3; ++i) out << (i ? ", '" : " '") << close[i] << "'";
    out << "?";
  } else if (with_writers == 0) {
    out << "; no topic has a writer there (is the pipeline running, on this domain? --pipeline FILE takes its "
           "domain and transport)";
  } else {
    out << "; " << with_writers << " topic(s) have writers there: wysiwyf topic list";
  }
  return out.str();
}

// Whether the reader still has a writer to hear from (after it had one): once every writer of
// the topic has gone, nothing more will come.
bool writers_gone(DataReader* reader) {
  SubscriptionMatchedStatus status;
  reader->get_subscription_matched_status(status);
  return status.total_count > 0 && status.current_count == 0;
}

// A reader of `topic`'s samples as DDS carried them (raw CDR, the writer's QoS), and how to
// print them: walked by the description of any type this build or a message library describes.
DataReader* subscribe(Session& s, const std::string& topic, const TopicInfo& info, SamplePrinter& print) {
  eprosima::fastrtps::types::DynamicType_ptr type;
  std::string searched;
  if (!find_dynamic_type(info.type, type, searched))
    throw std::runtime_error("topic '" + topic + "' carries " + info.type +
                             ", which neither this build nor a message library describes (searched " + searched + ")");
  print = [type](const RawCdr& sample) { return cdr_to_yaml(sample.bytes.data(), sample.bytes.size(), type); };
  Subscriber* sub = s.participant->create_subscriber(SUBSCRIBER_QOS_DEFAULT);
  DataReader* reader = open_raw_reader(s, sub, topic, info, 100, nullptr, StatusMask::none());
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
    std::cout << std::left << std::setw(32) << name << std::setw(40) << t.type << std::setw(8) << t.writer_ports()
              << t.reader_ports() << "\n";
  if (topics.empty())
    std::cerr << "no topics seen in DDS domain " << s.domain << " (transport " << s.transport << ") in " << wait
              << " s (is the pipeline running, on this domain? --pipeline FILE takes its domain and transport)\n";
  return 0;
}

int topic_echo(Args& args, const std::string& topic) {
  Session s;
  open(args, s);
  const long count = count_option(args, "--count");
  const double timeout = seconds_option(args, "--timeout", 10.0);
  const std::optional<std::string> field = args.value("--field");
  if (!args.unknown_options().empty()) throw UsageError("unknown option " + args.unknown_options().front());
  install_stop_signal_handlers();
  const auto info = s.discovery.wait_for_writer(
      topic, Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(timeout)));
  if (!info) {
    std::cerr << no_writer_message(s, topic, timeout, s.discovery.topics()) << "\n";
    return 1;
  }
  SamplePrinter print;
  DataReader* reader = subscribe(s, topic, *info, print);
  std::cout << "# topic " << topic << " (" << info->type << ")\n" << std::flush;
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
    RawCdr sample;
    while ((count == 0 || printed < count) && reader->take_next_sample(&sample, &si) == ReturnCode_t::RETCODE_OK) {
      if (!si.valid_data) continue;
      std::string text;
      try {
        text = print(sample);
        if (field) text = yaml_field(text, *field);
      } catch (const std::invalid_argument& e) {  // --field: every sample of the topic has the same fields
        std::cerr << e.what() << "\n";
        return 2;
      } catch (const std::runtime_error& e) {
        text = "# cannot read this sample: " + std::string(e.what()) + "\n";
      }
      std::cout << "---\n" << text << std::flush;
      ++printed;
    }
  }
  return printed > 0 ? 0 : 1;
}

// Samples of one topic as raw CDR with their arrival time and, for stamped types, their stamp.
class Arrivals final : public DataReaderListener {
 public:
  explicit Arrivals(bool stamped) : stamped_(stamped) {}
  struct Arrival {
    Clock::time_point at;
    std::optional<std::int64_t> stamp_ns;
  };
  void on_data_available(DataReader* reader) override {
    SampleInfo si;
    while (reader->take_next_sample(&sample_, &si) == ReturnCode_t::RETCODE_OK) {
      if (!si.valid_data) continue;
      Arrival a{Clock::now(), std::nullopt};
      // A std_msgs::Header first: the stamp is the 8 bytes after the encapsulation (little endian).
      if (stamped_ && sample_.bytes.size() >= 12 && sample_.bytes[1] == 0x01) {
        std::int64_t stamp = 0;
        std::memcpy(&stamp, sample_.bytes.data() + 4, 8);
        a.stamp_ns = stamp;
      }
      std::lock_guard<std::mutex> lock(mutex_);
      arrivals_.push_back(a);
      ++total;
    }
  }
  std::vector<Arrival> take() {
    std::lock_guard<std::mutex> lock(mutex_);
    return std::exchange(arrivals_, {});
  }
  std::atomic<std::uint64_t> total{0};

 private:
  bool stamped_;
  RawCdr sample_;
  std::mutex mutex_;
  std::vector<Arrival> arrivals_;
};

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
    std::cerr << no_writer_message(s, topic, timeout, s.discovery.topics()) << "\n";
    return 1;
  }
  // Any type: the samples are counted, not decoded; the stamp is read where the IDL says the
  // type starts with a header.
  std::string searched;
  const auto schema = idl_schema(info->type, searched);
  Arrivals arrivals(schema && schema->stamped);
  Subscriber* subscriber = s.participant->create_subscriber(SUBSCRIBER_QOS_DEFAULT);
  DataReader* reader = open_raw_reader(s, subscriber, topic, *info, 100, &arrivals, StatusMask::data_available());
  if (!reader) return 1;
  std::cout << "# topic " << topic << " (" << info->type << ") in domain " << s.domain
            << (schema && schema->stamped ? "; 'stamps': the rate on the pipeline's clock (sim time on the sim clock)"
                                          : "; the type has no header: wall-clock rate only")
            << (s.latency_budget.count() > 0 ? "; from a pipeline on the real clock samples arrive in batches, so "
                                               "min/max/std below measure the batching (--prompt: each sample's "
                                               "own arrival)"
                                             : "")
            << "\n"
            << std::flush;
  const auto start = Clock::now();
  auto window_end = start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(window));
  std::optional<Arrivals::Arrival> last;
  while (!stop_signal_received()) {
    if (duration > 0 && Clock::now() - start >= std::chrono::duration<double>(duration)) break;
    std::this_thread::sleep_until(std::min(window_end, Clock::now() + std::chrono::milliseconds(50)));
    if (Clock::now() < window_end) {
      if (writers_gone(reader) && arrivals.total == 0) break;
      continue;
    }
    window_end += std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(window));
    std::vector<Arrivals::Arrival> batch = arrivals.take();
    if (batch.empty()) {
      std::cout << "no new samples\n" << std::flush;
      if (writers_gone(reader)) {
        std::cerr << "every writer of topic '" << topic << "' has gone\n";
        break;
      }
      continue;
    }
    if (last) batch.insert(batch.begin(), *last);  // the gap across windows counts
    last = batch.back();
    if (batch.size() < 2) continue;
    std::vector<double> gaps;
    for (std::size_t i = 1; i < batch.size(); ++i)
      gaps.push_back(std::chrono::duration<double>(batch[i].at - batch[i - 1].at).count());
    double sum = 0, sq = 0, lo = gaps[0], hi = gaps[0];
    for (double g : gaps) sum += g, sq += g * g, lo = std::min(lo, g), hi = std::max(hi, g);
    const double mean = sum / gaps.size();
    const double sd = std::sqrt(std::max(0.0, sq / gaps.size() - mean * mean));
    std::cout << std::fixed << std::setprecision(3) << "rate " << 1.0 / mean << " Hz  min " << lo * 1e3 << " ms  max "
              << hi * 1e3 << " ms  std " << sd * 1e3 << " ms  n " << gaps.size();
    if (batch.front().stamp_ns && batch.back().stamp_ns && *batch.back().stamp_ns > *batch.front().stamp_ns)
      std::cout << "  |  stamps " << (batch.size() - 1) * 1e9 / (*batch.back().stamp_ns - *batch.front().stamp_ns)
                << " Hz over " << (*batch.back().stamp_ns - *batch.front().stamp_ns) * 1e-9 << " s";
    std::cout << "\n" << std::flush;
  }
  s.participant->delete_contained_entities();
  return arrivals.total > 0 ? 0 : 1;
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
