// `brdfrig rig calibrate lens`: the camera's intrinsics and distortion from photos of the
// printed ChArUco board (OpenCV's calibrateCameraCharuco), with the errors that say what the
// result is worth, and refusals where it would not be worth anything: a photo with too few
// board corners, a photo out of focus, or corners that leave too much of the frame uncovered
// (distortion is only known where the board was seen).
//
// The lens model is the pipeline's (geometry::Intrinsics): fx, fy, cx, cy and radial k1, k2;
// tangential distortion and k3 are held at 0 so the calibration estimates exactly what the
// reconstruction applies.
#pragma once

#include <filesystem>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "calibrate/board_detection.h"
#include "calibrate/charuco_spec.h"
#include "geometry/lens_calibration_file.h"

namespace brdfrig::calibrate {

struct CalibrationPhoto {
  std::string name;  // the file, for messages and the calibration file
  cv::Mat image;
};

// Reads photos: files as named, a directory as its image files (.png .tif .tiff .jpg .jpeg
// .exr), or a capture session's frames/ (or a simulation's photos/) when the directory itself
// holds none. Sorted by name; an unreadable image is an error naming it.
std::vector<CalibrationPhoto> LoadCalibrationPhotos(
    const std::vector<std::filesystem::path>& paths);

struct LensCalibrationOptions {
  CharucoSpec board;
  int min_corners = 12;                         // board corners a photo must show
  int min_photos = 4;                           // photos of the board
  double max_edge_width_px = 4;                 // a photo whose edges are wider is out of focus
  double min_coverage = 0.5;                    // share of the frame's grid cells holding a corner
  int coverage_columns = 8, coverage_rows = 6;  // the grid
  std::string camera_model, camera_serial;      // recorded in the file ("" = unknown)
  void Validate() const;                        // throws OptionsError
};

struct LensCalibrationResult {
  geometry::LensCalibration calibration;
  std::vector<BoardDetection> detections;
  std::string ToString() const;  // intrinsics, RMS, coverage, per-photo errors
};

// Throws brdfrig::Error saying which photo and which limit when it refuses.
LensCalibrationResult CalibrateLens(const std::vector<CalibrationPhoto>& photos,
                                    const LensCalibrationOptions& options);

// Share of the grid's cells (columns × rows over the frame) holding at least one corner.
double FrameCoverage(const std::vector<BoardDetection>& detections, cv::Size image_size,
                     int columns, int rows);

}  // namespace brdfrig::calibrate
