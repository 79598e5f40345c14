// wysiwyf record [TOPIC...] -o FILE: every sample of the chosen topics (all without a list), as
// DDS carried it, into an MCAP file with each type's IDL as its schema.
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <limits>
#include <map>
#include <atomic>
#include <cmath>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <deque>
#include <iostream>
#include <memory>
#include <thread>

#include "dds_session.hpp"
#include "idl_schemas.hpp"
#include "image_topic_writer.hpp"
#include "mcap/mcap_writer.hpp"
#include "raw_cdr_type.hpp"
#include "wysiwyf/dds.hpp"
#include "wysiwyf/runtime.hpp"

namespace wysiwyf::cli {

using namespace eprosima::fastdds::dds;

namespace {

std::uint64_t wall_ns() {
  return static_cast<std::uint64_t>(
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::system_clock::now().time_since_epoch())
          .count());
}

// The file and what goes into it. The DDS listeners only queue samples (they run on the
// transport's receive thread: blocking it on the disk would lose the next samples of every
// topic); a writer thread puts them into the file. The queue is bounded in bytes.
struct Recording {
  struct Pending {
    std::uint16_t channel;
    std::uint32_t sequence;
    std::uint64_t log_ns, publish_ns;
    std::vector<std::uint8_t> bytes;
    ImageTopicWriter* image;  // an image topic packed on the writer thread (--images), or null
    ImageTopicWriter::Packed packed = {};
  };
  static constexpr std::size_t kMaxQueuedBytes = std::size_t{1} << 30;

  std::mutex mutex;  // the writer (file)
  io::mcap::Writer writer;
  std::atomic<std::uint64_t> lost{0};        // DDS says samples were lost before reaching the recorder
  std::atomic<std::uint64_t> overflowed{0};  // samples dropped: the writer (compression, disk) fell 1 GiB behind

  Recording(const std::string& path, io::mcap::Compression compression)
      : writer(path, options(compression)), thread_([this] { write_loop(); }) {}
  ~Recording() { stop(); }
  static io::mcap::WriterOptions options(io::mcap::Compression compression) {
    io::mcap::WriterOptions o;
    o.library = "wysiwyf record";
    o.compression = compression;
    return o;
  }

  // The writer thread takes what came in this long in one go: a wake per batch, not per sample
  // (at 1 kHz a topic, a futex wake per sample was most of the recorder's time, in task switches).
  static constexpr std::chrono::milliseconds kWriteInterval{20};

  // From a listener: false if the queue is full (the sample is dropped and counted).
  bool enqueue(Pending&& p) {
    bool first = false;
    {
      std::lock_guard<std::mutex> lock(queue_mutex_);
      if (queued_bytes_ + p.bytes.size() > kMaxQueuedBytes) {
        overflowed.fetch_add(1);
        return false;
      }
      queued_bytes_ += p.bytes.size();
      first = queue_.empty();
      queue_.push_back(std::move(p));
    }
    if (first) cv_.notify_one();  // (the writer waits only on an empty queue)
    return true;
  }
  // A buffer for the next sample: one the writer thread is done with, so a listener copying a
  // megabyte image does not fault in fresh pages (it runs on the transport's receive thread).
  std::vector<std::uint8_t> buffer() {
    std::lock_guard<std::mutex> lock(queue_mutex_);
    if (free_.empty()) return {};
    std::vector<std::uint8_t> b = std::move(free_.back());
    free_.pop_back();
    return b;
  }
  // Writes what is queued and stops the writer thread.
  void stop() {
    {
      std::lock_guard<std::mutex> lock(queue_mutex_);
      if (stopping_) return;
      stopping_ = true;
    }
    cv_.notify_one();
    stop_cv_.notify_one();
    thread_.join();
  }

 private:
  void write_loop() {
    std::deque<Pending> batch;
    for (;;) {
      {
        std::unique_lock<std::mutex> lock(queue_mutex_);
        cv_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
        if (queue_.empty()) return;  // stopping, and all written
        batch.swap(queue_);
      }
      pack_images(batch, pack_cpu_ns_);
      const std::int64_t write_from = thread_cpu_ns();
      std::size_t bytes = 0;
      {
        std::lock_guard<std::mutex> lock(mutex);
        for (const auto& p : batch) {
          if (p.image)
            p.image->write(writer, p.sequence, p.log_ns, p.publish_ns, p.bytes, p.packed);
          else
            writer.write(p.channel, p.sequence, p.log_ns, p.publish_ns, p.bytes.data(), p.bytes.size());
          bytes += p.bytes.size();
        }
      }
      write_cpu_ns_ += thread_cpu_ns() - write_from;
      samples_bytes_ += bytes;
      std::unique_lock<std::mutex> lock(queue_mutex_);
      queued_bytes_ -= bytes;
      for (auto& p : batch)  // keep up to 256 buffers for reuse
        if (free_.size() < 256) free_.push_back(std::move(p.bytes));
      batch.clear();
      // Let the next batch gather (stop() cuts it short; a backlog left after this batch skips it).
      stop_cv_.wait_for(lock, kWriteInterval, [&] { return stopping_ || queued_bytes_ > kMaxQueuedBytes / 4; });
    }
  }
  // Packs a batch's images (--images): each topic's in order on one thread, the topics on as many
  // threads as there are cores (the codecs are most of the recorder's work); the file is written
  // after, in the batch's order.
  static void pack_images(std::deque<Pending>& batch, std::atomic<std::int64_t>& cpu_ns) {
    std::map<ImageTopicWriter*, std::vector<Pending*>> by_topic;
    for (auto& p : batch)
      if (p.image) by_topic[p.image].push_back(&p);
    std::vector<std::vector<Pending*>*> topics;
    for (auto& [image, samples] : by_topic) topics.push_back(&samples);
    std::atomic<std::size_t> next{0};
    const auto work = [&] {
      const std::int64_t from = thread_cpu_ns();
      for (std::size_t i; (i = next++) < topics.size();)
        for (Pending* p : *topics[i]) p->image->pack(p->bytes, p->packed);
      cpu_ns += thread_cpu_ns() - from;
    };
    const std::size_t n = std::min<std::size_t>(topics.size(), std::max(1u, std::thread::hardware_concurrency()));
    std::vector<std::thread> threads;
    for (std::size_t i = 1; i < n; ++i) threads.emplace_back(work);
    work();
    for (auto& t : threads) t.join();
  }

 public:
  // After stop(): the CPU time spent packing images and writing the file (compressing chunks),
  // whatever else the machine runs, and the samples' bytes taken: the recorder's throughput on one
  // core is their ratio.
  double pack_cpu_s() const { return static_cast<double>(pack_cpu_ns_.load()) * 1e-9; }
  double write_cpu_s() const { return static_cast<double>(write_cpu_ns_) * 1e-9; }
  std::uint64_t samples_bytes() const { return samples_bytes_; }

 private:
  static std::int64_t thread_cpu_ns() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return std::int64_t{t.tv_sec} * 1'000'000'000 + t.tv_nsec;
  }
  std::atomic<std::int64_t> pack_cpu_ns_{0};
  std::int64_t write_cpu_ns_ = 0;
  std::uint64_t samples_bytes_ = 0;
  std::mutex queue_mutex_;
  std::condition_variable cv_;       // the queue has samples
  std::condition_variable stop_cv_;  // stopping: write what is queued now
  std::deque<Pending> queue_;
  std::vector<std::vector<std::uint8_t>> free_;
  std::size_t queued_bytes_ = 0;
  bool stopping_ = false;
  std::thread thread_;
};

// One recorded topic: a reader of raw CDR and its channel in the file.
class TopicRecorder final : public DataReaderListener {
 public:
  TopicRecorder(Recording& rec, std::string topic, std::uint16_t channel, bool stamped,
                ImageTopicWriter* image = nullptr)
      : rec_(rec), topic_(std::move(topic)), channel_(channel), stamped_(stamped), image_(image) {}
  void on_data_available(DataReader* reader) override {
    SampleInfo info;
    for (;;) {
      if (sample_.bytes.capacity() == 0) sample_.bytes = rec_.buffer();
      if (reader->take_next_sample(&sample_, &info) != ReturnCode_t::RETCODE_OK) break;
      if (!info.valid_data) continue;
      const std::uint64_t now = wall_ns();
      // publish_time: the sample's own stamp on the pipeline's clock where its type starts with
      // a std_msgs::Header (sim time on the sim clock: what play --into replays by); else when
      // DDS says it was written.
      std::uint64_t publish = static_cast<std::uint64_t>(info.source_timestamp.to_ns());
      if (const auto stamp = stamped_ ? header_stamp(sample_.bytes) : std::nullopt; stamp && *stamp >= 0)
        publish = static_cast<std::uint64_t>(*stamp);
      if (rec_.enqueue({channel_, sequence_++, now, publish, std::move(sample_.bytes), image_})) ++messages;
      sample_.bytes = {};
    }
  }
  void on_requested_incompatible_qos(DataReader*, const RequestedIncompatibleQosStatus& status) override {
    std::cerr << "topic '" << topic_ << "': a writer was refused: " << dds::qos_policy_name(status.last_policy_id)
              << "\n";
  }
  void on_sample_lost(DataReader*, const SampleLostStatus& status) override {
    rec_.lost.fetch_add(static_cast<std::uint64_t>(status.total_count_change));
    lost.fetch_add(static_cast<std::uint64_t>(status.total_count_change));
  }
  std::atomic<std::uint64_t> messages{0}, lost{0};
  const ImageTopicWriter* image() const { return image_; }

 private:
  Recording& rec_;
  std::string topic_;
  std::uint16_t channel_;
  bool stamped_;
  ImageTopicWriter* image_;  // (in cmd_record's image_topics, which outlive the writer thread)
  RawCdr sample_;
  std::uint32_t sequence_ = 0;
};

}  // namespace

int cmd_record(Args args) {
  Session s;
  open(args, s);
  const auto out = args.value("-o").value_or(args.value("--output").value_or(""));
  const bool all = args.flag("--all");
  const double duration = number_option(args, "--duration", 0, 0, std::numeric_limits<double>::infinity(),
                                        "a number of seconds (0: until Ctrl-C)");
  const std::string compression_arg = args.value("--compression").value_or("zstd");
  const auto compression = io::mcap::parse_compression(compression_arg);
  if (!compression) throw UsageError("--compression: found '" + compression_arg + "'; expected zstd, lz4 or none");
  const std::string images = args.value("--images").value_or("lossless");
  if (images != "lossless" && images != "raw" && images != "video")
    throw UsageError("--images: found '" + images + "'; expected lossless, video or raw");
  const bool progress = !args.flag("--no-progress") && isatty(STDERR_FILENO);
  if (!args.unknown_options().empty()) throw UsageError("unknown option " + args.unknown_options().front());
  const std::vector<std::string> wanted = args.positional();
  if (out.empty()) throw UsageError("record: expected -o FILE.mcap");
  if (wanted.empty() && !all) throw UsageError("record: expected topic names, or --all for every topic");
  install_stop_signal_handlers();
  std::vector<std::unique_ptr<ImageTopicWriter>> image_topics;  // (before rec: its writer thread uses them)
  Recording rec(out, *compression);
  std::cerr << "recording " << (all ? "every topic" : std::to_string(wanted.size()) + " topic(s)") << " of domain "
            << s.domain << " (transport " << s.transport << ") into " << out << "\n";

  Subscriber* subscriber = s.participant->create_subscriber(SUBSCRIBER_QOS_DEFAULT);
  std::map<std::string, std::unique_ptr<TopicRecorder>> recorders;
  const auto start = Clock::now();
  auto next_line = start, next_flush = start;
  while (!stop_signal_received() && (duration == 0 || Clock::now() - start < std::chrono::duration<double>(duration))) {
    // Topics as writers announce them: each gets a channel (and its type a schema) once.
    for (const auto& [topic, info] : s.discovery.topics()) {
      if (info.writers.empty() || recorders.count(topic)) continue;
      if (!all && std::find(wanted.begin(), wanted.end(), topic) == wanted.end()) continue;
      std::string searched;
      const auto schema = idl_schema(info.type, searched);
      const std::map<std::string, std::string> metadata = {
          {"dds_type", info.type},
          {"reliability", info.reliability == RELIABLE_RELIABILITY_QOS ? "reliable" : "best_effort"},
          {"durability", info.durability == VOLATILE_DURABILITY_QOS ? "volatile" : "transient_local"},
          {"keyed", info.keyed ? "true" : "false"},
          {"ownership", info.one_writer ? "exclusive" : "shared"}};
      std::uint16_t schema_id = 0, channel = 0;
      ImageTopicWriter* image = nullptr;
      if (images != "raw" && info.type == "wysiwyf::msg::Image") {  // its channels come with its samples
        image_topics.push_back(std::make_unique<ImageTopicWriter>(
            topic, schema ? info.type : "", schema ? schema->text : "", metadata, images == "video"));
        image = image_topics.back().get();
      } else {
        std::lock_guard<std::mutex> lock(rec.mutex);
        if (schema) schema_id = rec.writer.add_schema(info.type, "omgidl", schema->text);
        channel = rec.writer.add_channel(schema_id, topic, "cdr", metadata);
      }
      if (!schema)
        std::cerr << "topic '" << topic << "': no IDL defines " << info.type << " (searched " << searched
                  << "); recorded without a schema\n";
      auto recorder = std::make_unique<TopicRecorder>(rec, topic, channel, schema && schema->stamped, image);
      // Deep: a burst waits here instead of being lost.
      if (!open_raw_reader(s, subscriber, topic, info, 100, recorder.get(),
                           StatusMask::data_available()
                               << StatusMask::sample_lost() << StatusMask::requested_incompatible_qos()))
        throw std::runtime_error("cannot read topic '" + topic + "' (" + info.type + ")");
      recorders.emplace(topic, std::move(recorder));
    }
    const auto now = Clock::now();
    if (now >= next_flush) {  // a chunk at least every half second: a killed recorder loses no more
      std::lock_guard<std::mutex> lock(rec.mutex);
      rec.writer.flush_chunk();
      next_flush = now + std::chrono::milliseconds(500);
    }
    if (progress && now >= next_line) {
      std::lock_guard<std::mutex> lock(rec.mutex);
      std::fprintf(stderr, "\r%zu topics  %llu messages  %.1f MB  %llu lost  %.1f s   ", recorders.size(),
                   static_cast<unsigned long long>(rec.writer.message_count()), rec.writer.bytes_written() / 1e6,
                   static_cast<unsigned long long>(rec.lost.load() + rec.overflowed.load()),
                   std::chrono::duration<double>(now - start).count());
      std::fflush(stderr);
      next_line = now + std::chrono::milliseconds(250);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  // Readers first (no listener runs after this), the queue, then the file's summary.
  s.participant->delete_contained_entities();
  rec.stop();
  {
    std::lock_guard<std::mutex> lock(rec.mutex);
    rec.writer.close();
  }
  if (progress) std::fprintf(stderr, "\n");
  std::cout << "recorded " << rec.writer.message_count() << " messages on " << recorders.size() << " topic(s), "
            << rec.writer.chunk_count() << " chunks, " << rec.writer.bytes_written() << " bytes into " << out
            << "; lost " << rec.lost.load() << " before the recorder, " << rec.overflowed.load()
            << " in it (the file's writer more than 1 GiB behind)\n";
  std::printf("CPU time: %.1f s packing images, %.1f s writing the file: %.0f MB of samples a second on one core\n",
              rec.pack_cpu_s(), rec.write_cpu_s(),
              static_cast<double>(rec.samples_bytes()) / 1e6 / std::max(rec.pack_cpu_s() + rec.write_cpu_s(), 1e-9));
  if (rec.writer.records_bytes() > 0)  // what the compression saved
    std::cout << "chunks " << (*compression == io::mcap::Compression::kNone ? "uncompressed" : compression_arg) << ": "
              << rec.writer.records_bytes() << " bytes of records in a file of " << rec.writer.bytes_written()
              << " bytes ("
              << std::lround(100.0 * static_cast<double>(rec.writer.bytes_written()) /
                             static_cast<double>(rec.writer.records_bytes()))
              << " %)\n";
  for (const auto& [topic, r] : recorders)
    std::cout << "  " << topic << ": " << r->messages.load()
              << (r->lost ? ", lost " + std::to_string(r->lost.load()) : "")
              << (r->image() ? " (" + r->image()->summary() + ")" : "") << "\n";
  if (!all)
    for (const auto& w : wanted)
      if (!recorders.count(w)) std::cerr << "topic '" << w << "' had no writer on domain " << s.domain << "\n";
  return rec.writer.message_count() > 0 ? 0 : 1;
}

}  // namespace wysiwyf::cli
