#include "bright_blobs/blob_detector.hpp"

#include <opencv2/imgproc.hpp>

namespace wysiwyf::vision {

namespace {

constexpr int kRing = 2;  // px around a blob that its centroid includes

// Mean brightness on the outer one-pixel border of `r`.
double ring_mean(const cv::Mat& luma, const cv::Rect& r) {
  double sum = 0;
  int n = 0;
  for (int x = r.x; x < r.x + r.width; ++x)
    sum += luma.at<std::uint8_t>(r.y, x) + luma.at<std::uint8_t>(r.y + r.height - 1, x), n += 2;
  for (int y = r.y + 1; y < r.y + r.height - 1; ++y)
    sum += luma.at<std::uint8_t>(y, r.x) + luma.at<std::uint8_t>(y, r.x + r.width - 1), n += 2;
  return n ? sum / n : 0.0;
}

}  // namespace

void BlobDetector::brightness_of(const cv::Mat& image, PixelLayout layout, cv::Rect roi, cv::Mat& luma) {
  const cv::Mat part = image(roi);
  if (s_.brightness != Brightness::kLuma && layout != PixelLayout::kMono8) {
    // The light's channel less the larger of the other two, saturated at 0.
    int channel = s_.brightness == Brightness::kRedExcess ? 0 : s_.brightness == Brightness::kGreenExcess ? 1 : 2;
    if (layout == PixelLayout::kBgr8) channel = 2 - channel;
    cv::split(part, channels_);
    cv::max(channels_[(channel + 1) % 3], channels_[(channel + 2) % 3], others_);
    cv::subtract(channels_[channel], others_, luma);  // 8-bit: saturates at 0
    return;
  }
  switch (layout) {
    case PixelLayout::kMono8: luma = part; break;  // a view: nothing to convert
    case PixelLayout::kRgb8: cv::cvtColor(part, luma, cv::COLOR_RGB2GRAY); break;
    case PixelLayout::kBgr8: cv::cvtColor(part, luma, cv::COLOR_BGR2GRAY); break;
  }
}

int BlobDetector::blobs_of(const cv::Mat& luma, cv::Point origin, std::vector<Blob>& out) {
  cv::threshold(luma, mask_, s_.threshold, 255, cv::THRESH_BINARY);
  const int n = cv::connectedComponentsWithStats(mask_, labels_, stats_, centroids_, 8, CV_32S);
  int cut = 0;
  for (int k = 1; k < n; ++k) {
    const int* st = stats_.ptr<int>(k);
    const cv::Rect box(st[cv::CC_STAT_LEFT], st[cv::CC_STAT_TOP], st[cv::CC_STAT_WIDTH], st[cv::CC_STAT_HEIGHT]);
    const int area = st[cv::CC_STAT_AREA];
    if (area < s_.min_area || area > s_.max_area) continue;
    if (area < s_.min_fill * box.area()) continue;
    if (box.x < kRing + 1 || box.y < kRing + 1 || box.x + box.width + kRing + 1 > luma.cols ||
        box.y + box.height + kRing + 1 > luma.rows) {  // it and its ring must lie inside, with a pixel to spare
      ++cut;
      continue;
    }
    // Centre of gravity of the brightness above the local background, over the blob and a
    // 2 px ring around it: all weights scale with the lighting, so the centroid does not move
    // when the lamp brightens or dims (a fixed threshold's crossing would, and a dome's outline
    // is not symmetric).
    const cv::Rect region =
        (box + cv::Point(-kRing, -kRing) + cv::Size(2 * kRing, 2 * kRing)) & cv::Rect(0, 0, luma.cols, luma.rows);
    const double background = ring_mean(luma, region);
    double sw = 0, su = 0, sv = 0;
    for (int y = region.y; y < region.y + region.height; ++y) {
      const int* lab = labels_.ptr<int>(y);
      const std::uint8_t* lum = luma.ptr<std::uint8_t>(y);
      for (int x = region.x; x < region.x + region.width; ++x) {
        if (lab[x] != k && lab[x] != 0) continue;  // another blob
        const double w = lum[x] - background;
        if (w > 0) sw += w, su += w * x, sv += w * y;
      }
    }
    if (sw <= 0) continue;
    out.push_back(Blob{origin.x + su / sw, origin.y + sv / sw, area, box + origin});
  }
  return cut;
}

void BlobDetector::detect_all(const cv::Mat& image, PixelLayout layout, std::vector<Blob>& out) {
  if (image.empty()) return;
  brightness_of(image, layout, cv::Rect(0, 0, image.cols, image.rows), luma_);
  blobs_of(luma_, cv::Point(0, 0), out);
}

bool BlobDetector::detect_in(const cv::Mat& image, PixelLayout layout, cv::Rect window, std::vector<Blob>& out) {
  const cv::Rect frame(0, 0, image.cols, image.rows);
  for (int attempt = 0; attempt < 2; ++attempt) {
    const cv::Rect roi = window & frame;
    if (roi.width < 3 || roi.height < 3) return false;
    brightness_of(image, layout, roi, luma_);
    const std::size_t before = out.size();
    const int cut = blobs_of(luma_, roi.tl(), out);
    if (cut == 0 || attempt == 1) return true;
    // A blob crossed the window's edge: look again in a window twice the size.
    out.resize(before);
    window = cv::Rect(window.x - window.width / 2, window.y - window.height / 2, 2 * window.width, 2 * window.height);
  }
  return true;
}

}  // namespace wysiwyf::vision
