#include "dashboard_feed.hpp"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "image/image_view.hpp"

namespace wysiwyf::bridge {

using Clock = std::chrono::steady_clock;
using json = nlohmann::json;

namespace {

constexpr auto kPlotPeriod = std::chrono::milliseconds(10);  // <= 100 points a second per plot
constexpr auto kModePeriod = std::chrono::milliseconds(200);
constexpr auto kFramePeriod = std::chrono::milliseconds(100);  // <= 10 video frames a second
constexpr std::size_t kMaxPlots = 8;

// A string member of a decoded sample, "" where it is missing or of another type (a sample comes
// from any writer on the domain).
std::string string_member(const json& sample, const char* key) {
  if (!sample.is_object()) return "";
  const auto it = sample.find(key);
  return it != sample.end() && it->is_string() ? it->get<std::string>() : "";
}

// JSON text for the page; a string that is not UTF-8 (a DDS string may hold any bytes) is
// replaced rather than thrown on.
std::string text(const json& j) { return j.dump(-1, ' ', false, json::error_handler_t::replace); }

}  // namespace

DashboardFeed::DashboardFeed(WsServer& server, DashboardOptions options)
    : server_(server), options_(std::move(options)) {
  for (const auto& p : options_.plots) {
    const auto colon = p.find(':');
    if (colon != std::string::npos) add_plot(p.substr(0, colon), p.substr(colon + 1));
  }
}

std::set<std::string> DashboardFeed::wanted_topics() const {
  std::set<std::string> topics{options_.diagnostics_topic, options_.mode_topic};
  if (server_.stats().dashboard_clients == 0) return topics;
  if (!options_.video_topic.empty()) topics.insert(options_.video_topic);
  std::lock_guard<std::mutex> lock(mutex_);
  for (const auto& [key, plot] : plots_) topics.insert(plot.topic);
  return topics;
}

void DashboardFeed::add_plot(const std::string& topic, const std::string& field) {
  if (plots_.size() >= kMaxPlots || topic.empty() || field.empty()) return;
  Plot& p = plots_[topic + ":" + field];
  p.topic = topic;
  p.field = field;
}

void DashboardFeed::on_sample(const std::string& topic, const std::string& type, const std::vector<std::uint8_t>& cdr,
                              std::uint64_t receive_ns) {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto now = Clock::now();
  if (topic == options_.video_topic) {
    if (now - frame_sent_ < kFramePeriod || server_.stats().dashboard_clients == 0) return;
    if (const msg::Image* image = type == "wysiwyf::msg::Image" ? decoder_.image(cdr) : nullptr) {
      video_frame(*image);
      frame_sent_ = now;
    }
    return;
  }
  const bool diagnostics = topic == options_.diagnostics_topic, mode = topic == options_.mode_topic;
  std::vector<Plot*> plots;
  for (auto& [key, p] : plots_)
    if (p.topic == topic && now - p.last >= kPlotPeriod) plots.push_back(&p);
  if (!diagnostics && !mode && plots.empty()) return;
  const auto sample = decoder_.to_json(type, cdr);
  if (!sample) return;
  if (diagnostics) {
    const std::string instance = string_member(*sample, "instance");
    std::string op = text(json{{"op", "diagnostics"}, {"sample", *sample}});
    diagnostics_[instance] = op;
    server_.dashboard_text(std::move(op));
  }
  if (mode) {
    const std::string name = string_member(*sample, "mode");  // e.g. MODE_SURFACE
    mode_ = text(json{{"op", "mode"}, {"sample", *sample}});
    if (name != mode_name_ || now - mode_sent_ >= kModePeriod) {
      server_.dashboard_text(mode_);
      mode_sent_ = now;
      mode_name_ = name;
    }
  }
  // Time on the pipeline's clock where the sample has a header (sim time on the sim clock).
  double t = static_cast<double>(receive_ns) * 1e-9;
  if (auto stamp = number_at(*sample, "header.stamp_ns")) t = *stamp * 1e-9;
  for (Plot* p : plots) {
    if (auto v = number_at(*sample, p->field)) {
      p->t.push_back(t);
      p->v.push_back(*v);
      p->last = now;
    }
  }
}

void DashboardFeed::video_frame(const msg::Image& m) {
  if (!vision::image::problem(m, {"rgb8", "bgr8", "rgba8", "mono8"}).empty()) return;
  const cv::Mat pixels = vision::image::view(m);
  cv::Mat bgr;
  const std::string enc = m.encoding().to_string();
  if (enc == "rgb8")
    cv::cvtColor(pixels, bgr, cv::COLOR_RGB2BGR);
  else if (enc == "rgba8")
    cv::cvtColor(pixels, bgr, cv::COLOR_RGBA2BGR);
  else
    bgr = pixels;
  if (bgr.cols > 640) cv::resize(bgr, bgr, cv::Size(640, bgr.rows * 640 / bgr.cols), 0, 0, cv::INTER_AREA);
  std::vector<std::uint8_t> jpeg;
  cv::imencode(".jpg", bgr, jpeg, {cv::IMWRITE_JPEG_QUALITY, 75});
  server_.dashboard_binary(std::move(jpeg));
}

void DashboardFeed::flush() {
  std::lock_guard<std::mutex> lock(mutex_);
  for (auto& [key, p] : plots_) {
    if (p.t.empty()) continue;
    server_.dashboard_text(text(json{{"op", "points"}, {"plot", key}, {"t", p.t}, {"v", p.v}}));
    p.t.clear();
    p.v.clear();
  }
}

std::vector<std::string> DashboardFeed::greeting() {
  std::lock_guard<std::mutex> lock(mutex_);
  json plots = json::array();
  for (const auto& [key, p] : plots_) plots.push_back(key);
  std::vector<std::string> out{text(json{{"op", "hello"},
                                         {"domain", options_.domain},
                                         {"video", options_.video_topic},
                                         {"mode_topic", options_.mode_topic},
                                         {"plots", plots}})};
  for (const auto& [instance, text] : diagnostics_) out.push_back(text);
  if (!mode_.empty()) out.push_back(mode_);
  return out;
}

void DashboardFeed::on_request(const DashboardRequest& request) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (request.op == DashboardRequest::Op::kPlot) add_plot(request.topic, request.field);
  if (request.op == DashboardRequest::Op::kUnplot) plots_.erase(request.topic + ":" + request.field);
}

}  // namespace wysiwyf::bridge
