// Finding the ChArUco board in a photo: its markers, the chessboard corners between them (to a
// fraction of a pixel), and how sharp the photo is at those corners.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "calibrate/charuco_spec.h"

namespace brdfrig::calibrate {

struct BoardDetection {
  std::string photo;  // name for messages
  cv::Size image_size;
  int markers = 0;                   // markers of the board found
  std::vector<cv::Point2f> corners;  // chessboard corners found (pixel centres at integers)
  std::vector<int> ids;              // their ids on the board
  // Median over the corners of how many pixels a black-to-white step takes (contrast over
  // the steepest gradient near the corner): about 1 in a sharp photo, 2.5 sigma under a
  // Gaussian blur of sigma pixels. 0 when no corner was found.
  double edge_width_px = 0;
};

// Any photo (8/16-bit or float, grey or BGR) as the 8-bit grey image ArUco detects in,
// stretched so its 99.5th percentile is white: a dark linear RAW-like photo is found as well as
// a JPEG.
cv::Mat DetectionImage(const cv::Mat& photo);

BoardDetection DetectBoard(const cv::Mat& photo, const CharucoSpec& spec, const std::string& name);

}  // namespace brdfrig::calibrate
