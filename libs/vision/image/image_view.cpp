#include "image/image_view.hpp"

#include <opencv2/core.hpp>

namespace wysiwyf::vision::image {

int cv_type(std::string_view e) {
  if (e == "rgb8" || e == "bgr8") return CV_8UC3;
  if (e == "rgba8" || e == "bgra8") return CV_8UC4;
  if (e == "mono8") return CV_8UC1;
  if (e == "mono16") return CV_16UC1;
  if (e == "32FC1") return CV_32FC1;
  return -1;
}

namespace {
std::string problem_of(const msg::Image& m, const std::string_view* encodings, std::size_t count) {
  const std::string_view encoding = m.encoding().c_str();
  bool accepted = false;
  std::string expected;
  for (std::size_t i = 0; i < count; ++i) {
    const std::string_view e = encodings[i];
    accepted = accepted || e == encoding;
    expected += (expected.empty() ? "" : " or ") + std::string(e);
  }
  if (!accepted) return "encoding '" + std::string(encoding) + "', expected " + expected;
  const int type = cv_type(encoding);
  if (type < 0) return "encoding '" + std::string(encoding) + "' is not one this build handles";
  if (m.width() == 0 || m.height() == 0)
    return "an empty image (" + std::to_string(m.width()) + "x" + std::to_string(m.height()) + ")";
  const std::size_t row = static_cast<std::size_t>(m.width()) * CV_ELEM_SIZE(type);
  if (m.step() < row)
    return "row step " + std::to_string(m.step()) + " shorter than a row of " + std::to_string(row) + " bytes";
  if (m.data().size() < static_cast<std::size_t>(m.step()) * m.height())
    return "data of " + std::to_string(m.data().size()) +
           " bytes, shorter than step x height = " + std::to_string(static_cast<std::size_t>(m.step()) * m.height());
  return {};
}
}  // namespace

std::string problem(const msg::Image& m, std::initializer_list<std::string_view> encodings) {
  return problem_of(m, encodings.begin(), encodings.size());
}

std::string problem(const msg::Image& m, const std::vector<std::string_view>& encodings) {
  return problem_of(m, encodings.data(), encodings.size());
}

std::string problem(const msg::Image& m, std::initializer_list<std::string_view> encodings, std::uint32_t width,
                    std::uint32_t height) {
  std::string why = problem(m, encodings);
  if (why.empty() && (m.width() != width || m.height() != height))
    why = "size " + std::to_string(m.width()) + "x" + std::to_string(m.height()) + ", expected " +
          std::to_string(width) + "x" + std::to_string(height);
  return why;
}

cv::Mat view(msg::Image& m) {
  return cv::Mat(static_cast<int>(m.height()), static_cast<int>(m.width()), cv_type(m.encoding().c_str()),
                 m.data().data(), m.step());
}

const cv::Mat view(const msg::Image& m) {
  // (cv::Mat has no const view: the const return keeps callers from writing through it)
  return view(const_cast<msg::Image&>(m));
}

cv::Mat allocate(msg::Image& m, int width, int height, std::string_view encoding) {
  const int type = cv_type(encoding);
  if (type < 0) throw std::invalid_argument("image::allocate: unknown encoding '" + std::string(encoding) + "'");
  m.width(static_cast<std::uint32_t>(width));
  m.height(static_cast<std::uint32_t>(height));
  m.encoding(std::string(encoding));
  m.is_bigendian(0);
  m.step(static_cast<std::uint32_t>(width * CV_ELEM_SIZE(type)));
  m.data().resize(static_cast<std::size_t>(m.step()) * static_cast<std::size_t>(height));
  return view(m);
}

}  // namespace wysiwyf::vision::image
