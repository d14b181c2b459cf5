// The printed ChArUco calibration board: its squares, markers and dictionary, and where it sits
// on the printed page. The one description the printer (`brdfrig target print`), the simulator
// (a scene's `board:`) and the lens calibration (`brdfrig rig calibrate lens`) share, so the
// board photographed is the board printed and the board detected.
//
// Board coordinates are OpenCV's (cv::aruco::CharucoBoard, 4.6): origin at the top-left outer
// corner of the chessboard as printed, x to the right, y down the page, metres; the square at
// the origin is black and the markers sit in the white squares.
#pragma once

#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <opencv2/core/cvstd_wrapper.hpp>
#include <string>

#include "common/yaml_reader.h"

// Declared, not included: <opencv2/aruco/charuco.hpp> brings calib3d and features2d, and this
// header reaches most of the project through sim/scene.h. Code that draws or detects a board
// includes it itself.
namespace cv::aruco {
class Dictionary;
class CharucoBoard;
}  // namespace cv::aruco

namespace brdfrig::calibrate {

// An ArUco dictionary by its OpenCV name (DICT_4X4_50 ... DICT_ARUCO_ORIGINAL). Throws Error
// listing the known names for another name.
cv::Ptr<cv::aruco::Dictionary> DictionaryNamed(const std::string& name);
// The number of markers the dictionary holds.
int DictionarySize(const std::string& name);

struct CharucoSpec {
  int squares_x = 11, squares_y = 8;  // chessboard squares across and down
  double square_m = 0.020;            // side of a chessboard square
  double marker_m = 0.015;            // side of a marker (black border included)
  std::string dictionary = "DICT_5X5_100";
  // The page it is printed on (A4 landscape by default): the board is centred across and sits
  // above a strip that holds the scale bar.
  double page_width_m = 0.297, page_height_m = 0.210;

  // Throws OptionsError naming the field: too few squares, markers not smaller than squares,
  // more markers than the dictionary holds, a board that does not fit its page.
  void Validate() const;

  int Markers() const { return squares_x * squares_y / 2; }
  int InnerCorners() const { return (squares_x - 1) * (squares_y - 1); }
  double BoardWidth() const { return squares_x * square_m; }
  double BoardHeight() const { return squares_y * square_m; }
  // The board origin (top-left outer corner) on the page, metres from the page's top-left.
  Eigen::Vector2d OriginOnPage() const;

  cv::Ptr<cv::aruco::CharucoBoard> MakeBoard() const;

  nlohmann::json ToJson() const;
  // Reads what ToJson wrote; `source` names the file for errors.
  static CharucoSpec FromJson(const nlohmann::json& j, const std::string& source);
  // Reads a YAML mapping with the same keys (square_mm, marker_mm and page_mm in millimetres);
  // absent keys keep their defaults. Errors name file:line.
  static CharucoSpec FromYaml(const YamlNode& node);
};

// Height of the strip under the board that holds the scale bar (metres).
inline constexpr double kScaleStripM = 0.018;

}  // namespace brdfrig::calibrate
