#pragma once
// Finds small lights in a camera image (the plate's lamps, a fingertip LED): bright blobs with
// sub-pixel, intensity-weighted centroids. Either over the whole frame (acquisition) or inside
// small search windows only (tracking: no pixel outside the windows is read). Brightness is the
// luma, or for a coloured light how far its colour channel exceeds the larger of the other two
// (white lamps and grey metal then read as dark, a green LED as bright).
#include <opencv2/core.hpp>

#include <vector>

namespace wysiwyf::vision {

// A bright blob. (u, v): centroid in pixels (pixel centres at integers), weighted by brightness
// above the local background (the mean of a ring around the blob); area: pixels above the
// threshold.
struct Blob {
  double u = 0, v = 0;
  int area = 0;
  cv::Rect box;
};

// Pixel layouts the detector reads.
enum class PixelLayout { kRgb8, kBgr8, kMono8 };

// What brightness is: the Rec. 601 luma, or one colour channel's excess over the other two
// (mono8 images: always the luma).
enum class Brightness { kLuma, kRedExcess, kGreenExcess, kBlueExcess };

// What counts as a light.
struct BlobSettings {
  Brightness brightness = Brightness::kLuma;
  int threshold = 215;    // brightness a light's pixel exceeds (the lit plate's luma stays below ~195)
  int min_area = 3;       // pixels; smaller blobs are noise
  int max_area = 4000;    // pixels; larger ones are not lamps (glare, a white sheet)
  double min_fill = 0.3;  // area / bounding box area: rejects streaks and thin lines
};

class BlobDetector {
 public:
  using Settings = BlobSettings;

  explicit BlobDetector(Settings s = {}) : s_(s) {}
  const Settings& settings() const { return s_; }

  // Every light-like blob of the image, appended to `out`.
  void detect_all(const cv::Mat& image, PixelLayout layout, std::vector<Blob>& out);
  // The light-like blobs inside `window` (clipped to the image), appended to `out`. A blob cut by
  // the window's edge makes the window grow (twice its size, once); one still cut, or cut by the
  // image border, is left out (its centroid would be biased). Returns false when the window
  // lies outside the image.
  bool detect_in(const cv::Mat& image, PixelLayout layout, cv::Rect window, std::vector<Blob>& out);

 private:
  void brightness_of(const cv::Mat& image, PixelLayout layout, cv::Rect roi, cv::Mat& luma);
  // Labels the bright pixels of `luma` (whose top-left pixel is `origin` in the image) and
  // appends the acceptable blobs that do not touch its edge; returns how many did touch it.
  int blobs_of(const cv::Mat& luma, cv::Point origin, std::vector<Blob>& out);

  Settings s_;
  cv::Mat luma_, mask_, labels_, stats_, centroids_, channels_[3], others_;  // reused between calls
};

}  // namespace wysiwyf::vision
