#pragma once
// The ChArUco board the camera calibrations look at: its layout (squares, their size, the markers'
// size and dictionary), OpenCV's board for detection, and the board's printable image drawn from
// the board's own marker positions, so that a texture pixel's place on the board is exact (the
// simulated views and a print at a known scale both rely on it).
#include <string>
#include <vector>

#include <opencv2/aruco/charuco.hpp>
#include <opencv2/core.hpp>

namespace wysiwyf::vision::calibration {

// The default fits an A4 sheet printed at 100 %: 10 x 7 squares of 28 mm (280 x 196 mm).
struct CharucoSpec {
  int squares_x = 10;                        // squares along the board's x
  int squares_y = 7;                         // and y
  double square = 0.028;                     // m, a square's side
  double marker = 0.021;                     // m, a marker's side (inside a white square)
  int dictionary = cv::aruco::DICT_5X5_100;  // cv::aruco::PREDEFINED_DICTIONARY_NAME
};

// The spec checked: 3..30 squares each way, 5 mm..1 m squares, markers 30..90 % of a square, a
// dictionary with a marker for every white square. Empty when usable, else what is wrong.
std::string problem(const CharucoSpec& spec);

class CharucoTarget {
 public:
  // Throws std::invalid_argument with problem(spec) when the spec is unusable.
  explicit CharucoTarget(const CharucoSpec& spec);

  const CharucoSpec& spec() const { return spec_; }
  const cv::Ptr<cv::aruco::CharucoBoard>& board() const { return board_; }
  // The inner chessboard corners in the board frame (m, z = 0), indexed by charuco id.
  const std::vector<cv::Point3f>& corners() const { return board_->chessboardCorners; }
  // The board's size, m.
  double width() const { return spec_.squares_x * spec_.square; }
  double height() const { return spec_.squares_y * spec_.square; }

  // The board's image, `pixels_per_square` per square, 8-bit grey: texture pixel (i, j) covers
  // board x in [i, i+1) * square / pixels_per_square, y alike (texture_y_flipped() says which way).
  cv::Mat texture(int pixels_per_square) const;
  // Whether the board's y runs up the texture (OpenCV's board frame is y up in some versions).
  bool texture_y_flipped() const { return flipped_; }

 private:
  CharucoSpec spec_;
  cv::Ptr<cv::aruco::CharucoBoard> board_;
  bool flipped_ = false;
};

}  // namespace wysiwyf::vision::calibration
