// wysiwyf play FILE.mcap: the recorded samples back, either into a pipeline run in this process
// on the sim clock (--into PIPELINE: each sample reaches its readers in the step of its recorded
// stamp, so a recorded run replays bit for bit), or onto a DDS domain on the real clock, spaced
// as they were recorded (divided by --rate), for any running pipeline or tool.
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include <algorithm>
#include <limits>
#include <cmath>
#include <iostream>
#include <sstream>
#include <thread>

#include "dds_session.hpp"
#include "dynamic_keys.hpp"
#include "image_replay.hpp"
#include "mcap/mcap_reader.hpp"
#include "raw_cdr_type.hpp"
#include "wysiwyf/dds.hpp"
#include "wysiwyf/loader.hpp"
#include "wysiwyf/pipeline_spec.hpp"
#include "wysiwyf/runtime.hpp"
#include "wysiwyf/validator.hpp"

namespace wysiwyf::cli {

using namespace eprosima::fastdds::dds;

namespace {

std::vector<std::string> split_list(const std::string& s) {
  std::vector<std::string> out;
  std::istringstream in(s);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

bool selected(const std::vector<std::string>& topics, const std::string& topic) {
  return topics.empty() || std::find(topics.begin(), topics.end(), topic) != topics.end();
}

// The file as a SampleFeed: messages in file order, each due at its publish time (the stamp on
// the recorded pipeline's clock); with loop, the file again after its last stamp.
class McapFeed final : public SampleFeed {
 public:
  McapFeed(const std::string& path, std::vector<std::string> topics, bool loop)
      : reader_(path), topics_(std::move(topics)), loop_(loop) {
    advance();
  }
  void due(std::int64_t t_ns, const Deliver& deliver) override {
    while (has_ && static_cast<std::int64_t>(next_.publish_time + offset_) <= t_ns) {
      const auto& channel = reader_.channels().at(next_.channel);
      if (images_.unpack(channel, next_)) {
        deliver(channel.topic, next_.data.data(), next_.data.size());
        ++played_;
      }
      advance();
    }
  }
  std::uint64_t played() const { return played_; }
  const ImageReplay& images() const { return images_; }
  const io::mcap::Reader& reader() const { return reader_; }

 private:
  void advance() {
    while (true) {
      has_ = reader_.next(next_);
      if (!has_) {
        if (!loop_ || played_ == 0) return;
        offset_ += last_ + 1;  // the next pass starts after this one's last stamp
        reader_.rewind();
        continue;
      }
      last_ = std::max(last_, next_.publish_time);
      const auto it = reader_.channels().find(next_.channel);
      if (it != reader_.channels().end() && selected(topics_, it->second.topic)) return;
    }
  }

  io::mcap::Reader reader_;
  std::vector<std::string> topics_;
  bool loop_;
  io::mcap::Message next_;
  ImageReplay images_;
  bool has_ = false;
  std::uint64_t offset_ = 0, last_ = 0, played_ = 0;
};

int play_into(const std::string& file, const std::string& pipeline, const std::vector<std::string>& sets,
              const std::vector<std::string>& topics, bool loop, double rate, double start_after) {
  Loader loader;
  std::vector<std::string> all_sets = sets;
  if (rate >= 0) all_sets.push_back("clock.pace=" + std::to_string(rate));
  const PipelineSpec spec = load_pipeline(pipeline, all_sets);
  if (spec.clock_mode() != ClockMode::kSim)
    throw UsageError(
        "play --into: the pipeline runs on the real clock; expected a sim-clock pipeline (on the real "
        "clock, play onto its domain without --into)");
  const ValidationResult v = validate_pipeline(spec, loader);
  for (const auto& e : v.errors) std::cerr << e.str() << "\n";
  if (!v.errors.empty()) return 2;
  McapFeed feed(file, topics, loop);
  install_stop_signal_handlers();
  RunOptions options;
  options.feed = &feed;
  options.start_after_s = start_after;
  Runtime runtime(spec, loader, options);
  const RunResult r = runtime.run();
  std::cout << "played " << r.fed_samples << " of " << feed.played() << " samples from " << file << " into '"
            << spec.name.value << "'; stopped: " << (r.ok ? r.stop_reason : "fault") << " at t=" << r.sim_time_ns * 1e-9
            << " s\n";
  for (const auto& [topic, why] : r.feed_refused) std::cout << "  not played on '" << topic << "': " << why << "\n";
  feed.images().report(std::cout);
  for (const auto& line : r.dds_problems) std::cout << "  dds: " << line << "\n";
  if (!feed.reader().problem().empty()) std::cout << "  " << file << ": " << feed.reader().problem() << "\n";
  if (!r.ok) {
    std::cerr << "error: " << r.error << "\n";
    return 1;
  }
  return 0;
}

int play_onto_domain(Args& args, const std::string& file, const std::vector<std::string>& topics, bool loop,
                     double rate) {
  Session s;
  open(args, s);
  if (!args.unknown_options().empty()) throw UsageError("unknown option " + args.unknown_options().front());
  install_stop_signal_handlers();
  io::mcap::Reader reader(file);
  Publisher* publisher = s.participant->create_publisher(PUBLISHER_QOS_DEFAULT);
  std::map<std::uint16_t, DataWriter*> writers;  // by channel; null: not played
  RawCdr sample;
  ImageReplay images;
  std::uint64_t played = 0;
  const double speed = rate > 0 ? rate : 1.0;
  do {
    reader.rewind();
    const auto start = Clock::now();
    std::optional<std::uint64_t> first;
    io::mcap::Message m;
    while (!stop_signal_received() && reader.next(m)) {
      auto [it, added] = writers.try_emplace(m.channel, nullptr);
      if (added) {
        const io::mcap::Channel& ch = reader.channels().at(m.channel);
        const auto meta = [&](const char* key) {
          const auto f = ch.metadata.find(key);
          return f == ch.metadata.end() ? std::string() : f->second;
        };
        if (!selected(topics, ch.topic)) continue;
        if (ch.message_encoding != "cdr" || meta("dds_type").empty()) {
          std::cerr << "topic '" << ch.topic << "': not a DDS recording (encoding " << ch.message_encoding
                    << "); skipped\n";
          continue;
        }
        const bool keyed = meta("keyed") == "true";
        RawCdrType::KeyOf key_of;
        if (keyed) {  // each sample's instance from its bytes, through the type's description
          std::string searched;
          key_of = dynamic_key_of(meta("dds_type"), searched);
          if (!key_of) {
            std::cerr << "topic '" << ch.topic << "': a keyed type (" << meta("dds_type")
                      << ") whose keys cannot be computed: no description of it (searched " << searched
                      << "); skipped\n";
            continue;
          }
        }
        TypeSupport support(new RawCdrType(meta("dds_type"), keyed, std::move(key_of)));
        support.register_type(s.participant, meta("dds_type"));
        Topic* t = s.participant->create_topic(ch.topic, meta("dds_type"), TOPIC_QOS_DEFAULT);
        Qos qos = Qos::reliable(16);
        if (meta("reliability") == "best_effort") qos.reliability = Reliability::kBestEffort;
        if (meta("durability") == "transient_local") qos.durability = Durability::kTransientLocal;
        // A topic that takes one writer (a robot's setpoint) is written as its writer did, so
        // readers that ask for exclusive ownership match the replay.
        qos.single_writer = meta("ownership") == "exclusive";
        DataWriterQos wq = dds::writer_qos(qos, keyed ? dds::kKeyedTopicInstances : 1);
        wq.endpoint().history_memory_policy = eprosima::fastrtps::rtps::DYNAMIC_REUSABLE_MEMORY_MODE;
        wq.data_sharing().off();
        it->second = t ? publisher->create_datawriter(t, wq) : nullptr;
        if (!it->second) throw std::runtime_error("cannot write topic '" + ch.topic + "'");
      }
      if (!it->second || !images.unpack(reader.channels().at(m.channel), m)) continue;
      if (!first) first = m.log_time;
      std::this_thread::sleep_until(start +
                                    std::chrono::nanoseconds(static_cast<std::int64_t>((m.log_time - *first) / speed)));
      sample.bytes.swap(m.data);
      if (it->second->write(&sample)) ++played;
    }
  } while (loop && !stop_signal_received() && played > 0);
  std::cout << "played " << played << " samples from " << file << " onto domain " << s.domain << "\n";
  images.report(std::cout);
  if (!reader.problem().empty()) std::cout << "  " << file << ": " << reader.problem() << "\n";
  return played > 0 ? 0 : 1;
}

}  // namespace

int cmd_play(Args args) {
  const auto file = args.take_front();
  if (!file) throw UsageError("play: expected an MCAP file");
  const auto into = args.value("--into");
  const std::vector<std::string> sets = args.values("--set");
  const std::vector<std::string> topics = split_list(args.value("--topics").value_or(""));
  const bool loop = args.flag("--loop");
  const double rate = number_option(args, "--rate", -1, 0, std::numeric_limits<double>::infinity(),
                                    "a number >= 0 (1: as recorded, 0: as fast as possible)");
  const double start_after = number_option(args, "--start-after", 0, 0, 3600, "seconds from 0 to 3600");
  if (into) {
    if (!args.unknown_options().empty()) throw UsageError("unknown option " + args.unknown_options().front());
    return play_into(*file, *into, sets, topics, loop, rate, start_after);
  }
  return play_onto_domain(args, *file, topics, loop, rate);
}

}  // namespace wysiwyf::cli
