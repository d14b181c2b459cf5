#include "calibrate/board_detection.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/aruco/charuco.hpp>
#include <opencv2/imgproc.hpp>

namespace brdfrig::calibrate {
namespace {

// Half-size of the window around a corner in which the edge width is measured: wide enough to
// see both the black and the white square under a few pixels of blur.
constexpr int kSharpnessWindow = 7;

double EdgeWidthAt(const cv::Mat& grey, const cv::Mat& gradient, cv::Point2f corner) {
  const int r = kSharpnessWindow;
  const cv::Rect window(static_cast<int>(std::lround(corner.x)) - r,
                        static_cast<int>(std::lround(corner.y)) - r, 2 * r + 1, 2 * r + 1);
  if ((window & cv::Rect(0, 0, grey.cols, grey.rows)) != window) return -1;
  const cv::Mat patch = grey(window);  // one header: its iterators must share it
  std::vector<float> values(patch.begin<float>(), patch.end<float>());
  std::sort(values.begin(), values.end());
  const double contrast = values[values.size() * 95 / 100] - values[values.size() * 5 / 100];
  double steepest = 0;
  cv::minMaxLoc(gradient(window), nullptr, &steepest);
  if (!(contrast > 0) || !(steepest > 0)) return -1;
  return contrast / steepest;
}

double MedianEdgeWidth(const cv::Mat& detection_image, const std::vector<cv::Point2f>& corners) {
  cv::Mat grey, gx, gy, magnitude;
  detection_image.convertTo(grey, CV_32F);
  // Sobel's 3×3 kernel sums 8 × the derivative: scale to intensity per pixel.
  cv::Sobel(grey, gx, CV_32F, 1, 0, 3, 1.0 / 8);
  cv::Sobel(grey, gy, CV_32F, 0, 1, 3, 1.0 / 8);
  cv::magnitude(gx, gy, magnitude);
  std::vector<double> widths;
  for (const cv::Point2f& c : corners) {
    const double w = EdgeWidthAt(grey, magnitude, c);
    if (w > 0) widths.push_back(w);
  }
  if (widths.empty()) return 0;
  std::nth_element(widths.begin(), widths.begin() + widths.size() / 2, widths.end());
  return widths[widths.size() / 2];
}

// OpenCV 4.6's interpolateCornersCharuco returns corners half a pixel right of and below the
// chessboard's saddle points (pixel centres at integers, OpenCV's convention and ours: a
// pixel-aligned board's corner between pixels 99 and 100 comes back at 100, not 99.5; found
// against the simulator's truth, tests/calibrate/lens_refusal_test). That bias would move the
// principal point by half a pixel, so the corners are refined again from where they were
// placed, with a window that stays inside the white margin between the corner and the markers
// of the squares around it (their edges would pull the corner), in the smallest square seen.
void RefineSaddlePoints(const cv::Mat& image, const CharucoSpec& spec,
                        std::vector<cv::Point2f>* corners) {
  if (corners->size() < 2) return;
  double nearest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < corners->size(); ++i) {
    for (std::size_t j = i + 1; j < corners->size(); ++j) {
      nearest = std::min(nearest, static_cast<double>(cv::norm((*corners)[i] - (*corners)[j])));
    }
  }
  const double margin = 0.5 * (spec.square_m - spec.marker_m) / spec.square_m;
  const int half = std::clamp(static_cast<int>(0.9 * margin * nearest), 2, 12);
  cv::cornerSubPix(image, *corners, cv::Size(half, half), cv::Size(-1, -1),
                   cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 100, 1e-4));
}

}  // namespace

cv::Mat DetectionImage(const cv::Mat& photo) {
  cv::Mat grey;
  if (photo.channels() == 3) {
    cv::cvtColor(photo, grey, cv::COLOR_BGR2GRAY);
  } else if (photo.channels() == 4) {
    cv::cvtColor(photo, grey, cv::COLOR_BGRA2GRAY);
  } else {
    grey = photo;
  }
  cv::Mat values;
  grey.convertTo(values, CV_32F);
  cv::Mat sorted = values.reshape(1, 1).clone();
  const int n = static_cast<int>(sorted.total());
  float* begin = sorted.ptr<float>();
  std::nth_element(begin, begin + n * 995 / 1000, begin + n);
  const double white = std::max(1e-12, static_cast<double>(begin[n * 995 / 1000]));
  cv::Mat out;
  values.convertTo(out, CV_8U, 255.0 / white);
  return out;
}

BoardDetection DetectBoard(const cv::Mat& photo, const CharucoSpec& spec, const std::string& name) {
  BoardDetection d;
  d.photo = name;
  d.image_size = photo.size();
  const cv::Mat image = DetectionImage(photo);
  const cv::Ptr<cv::aruco::CharucoBoard> board = spec.MakeBoard();
  std::vector<std::vector<cv::Point2f>> marker_corners, rejected;
  std::vector<int> marker_ids;
  const cv::Ptr<cv::aruco::DetectorParameters> parameters = cv::aruco::DetectorParameters::create();
  cv::aruco::detectMarkers(image, board->dictionary, marker_corners, marker_ids, parameters,
                           rejected);
  // Markers recovered with the board's layout (a marker missed at first, e.g. under glare).
  cv::aruco::refineDetectedMarkers(image, board, marker_corners, marker_ids, rejected);
  d.markers = static_cast<int>(marker_ids.size());
  if (marker_ids.empty()) return d;
  // Without a camera model the corners are placed by local homographies of the markers and
  // refined to a fraction of a pixel on the chessboard's saddle points.
  cv::Mat corners, ids;
  cv::aruco::interpolateCornersCharuco(marker_corners, marker_ids, image, board, corners, ids);
  for (int i = 0; i < corners.rows; ++i) {
    d.corners.push_back(corners.at<cv::Point2f>(i));
    d.ids.push_back(ids.at<int>(i));
  }
  RefineSaddlePoints(image, spec, &d.corners);
  d.edge_width_px = MedianEdgeWidth(image, d.corners);
  return d;
}

}  // namespace brdfrig::calibrate
