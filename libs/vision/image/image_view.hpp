#pragma once
// The one edge between Image messages and OpenCV: check an incoming image, view its pixels as a
// cv::Mat without copying, and size an outgoing one. Encodings as in ROS: rgb8, bgr8, rgba8,
// mono8, mono16, 32FC1.
#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "wysiwyf/msgs.hpp"

namespace wysiwyf::vision::image {

// The OpenCV type of an encoding (rgb8 -> CV_8UC3), or -1 for an encoding not handled here.
int cv_type(std::string_view encoding);

// What is wrong with `m` for a reader that takes one of `encodings`: another or an unknown
// encoding, no pixels, a row step shorter than a row, data shorter than step x height. Empty
// when nothing is.
std::string problem(const msg::Image& m, std::initializer_list<std::string_view> encodings);
std::string problem(const msg::Image& m, const std::vector<std::string_view>& encodings);
// As above, and the image must also be `width` x `height` (the size of another stream it goes with).
std::string problem(const msg::Image& m, std::initializer_list<std::string_view> encodings, std::uint32_t width,
                    std::uint32_t height);

// The pixels of an image that passed problem(), sharing its buffer (the view is valid while the
// message keeps its data).
cv::Mat view(msg::Image& m);
const cv::Mat view(const msg::Image& m);

// Sizes `m` for a width x height image of `encoding` (no reallocation once it has that size) and
// returns a view of its pixels to write into.
cv::Mat allocate(msg::Image& m, int width, int height, std::string_view encoding);

}  // namespace wysiwyf::vision::image
