#include "calibrate/lens_calibration.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <opencv2/aruco/charuco.hpp>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <set>
#include <sstream>

#include "common/error.h"
#include "common/option_check.h"
#include "common/utc_time.h"

namespace brdfrig::calibrate {
namespace {

namespace fs = std::filesystem;

bool IsImage(const fs::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  static const std::set<std::string> kImages = {".png", ".tif", ".tiff", ".jpg", ".jpeg", ".exr"};
  return kImages.count(ext) > 0;
}

std::vector<fs::path> ImagesIn(const fs::path& dir) {
  std::vector<fs::path> images;
  for (const fs::directory_entry& e : fs::directory_iterator(dir)) {
    if (e.is_regular_file() && IsImage(e.path())) images.push_back(e.path());
  }
  std::sort(images.begin(), images.end());
  return images;
}

std::string Fixed(double v, int decimals) {
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, v);
  return buffer;
}

}  // namespace

std::vector<CalibrationPhoto> LoadCalibrationPhotos(const std::vector<fs::path>& paths) {
  std::vector<fs::path> files;
  for (const fs::path& p : paths) {
    std::error_code ec;
    if (fs::is_directory(p, ec)) {
      std::vector<fs::path> images = ImagesIn(p);
      for (const char* sub : {"frames", "photos"}) {
        if (images.empty() && fs::is_directory(p / sub, ec)) images = ImagesIn(p / sub);
      }
      if (images.empty()) throw Error(p.string() + ": no photos in this directory");
      files.insert(files.end(), images.begin(), images.end());
    } else if (fs::is_regular_file(p, ec)) {
      files.push_back(p);
    } else {
      throw Error(p.string() + ": no such photo or directory");
    }
  }
  std::vector<CalibrationPhoto> photos;
  for (const fs::path& f : files) {
    cv::Mat image = cv::imread(f.string(), cv::IMREAD_UNCHANGED | cv::IMREAD_ANYDEPTH);
    if (image.empty()) throw FileError(f.string(), "not an image OpenCV can read");
    photos.push_back({f.string(), std::move(image)});
  }
  return photos;
}

void LensCalibrationOptions::Validate() const {
  board.Validate();
  CheckOption(min_corners >= 6, "LensCalibrationOptions.min_corners", min_corners, ">= 6");
  CheckOption(min_photos >= 3, "LensCalibrationOptions.min_photos", min_photos,
              ">= 3 (a plane seen from fewer views cannot fix the intrinsics)");
  CheckOption(max_edge_width_px > 0, "LensCalibrationOptions.max_edge_width_px", max_edge_width_px,
              "> 0");
  CheckOption(min_coverage >= 0 && min_coverage <= 1, "LensCalibrationOptions.min_coverage",
              min_coverage, "in [0, 1]");
  CheckOption(coverage_columns >= 1 && coverage_rows >= 1,
              "LensCalibrationOptions.coverage_columns", coverage_columns,
              ">= 1 (and coverage_rows too)");
}

double FrameCoverage(const std::vector<BoardDetection>& detections, cv::Size image_size,
                     int columns, int rows) {
  std::set<int> cells;
  for (const BoardDetection& d : detections) {
    for (const cv::Point2f& c : d.corners) {
      const int i = std::clamp(static_cast<int>(c.x * columns / image_size.width), 0, columns - 1);
      const int j = std::clamp(static_cast<int>(c.y * rows / image_size.height), 0, rows - 1);
      cells.insert(j * columns + i);
    }
  }
  return static_cast<double>(cells.size()) / (columns * rows);
}

std::string LensCalibrationResult::ToString() const {
  const geometry::LensCalibration& c = calibration;
  const geometry::Intrinsics& k = c.intrinsics;
  const geometry::Intrinsics& s = c.uncertainty;
  std::ostringstream out;
  out << "lens calibration from " << c.photos.size() << " photos, " << c.corners << " corners, "
      << k.width << "x" << k.height << "\n"
      << "  fx " << Fixed(k.fx, 2) << " ± " << Fixed(s.fx, 2) << "  fy " << Fixed(k.fy, 2) << " ± "
      << Fixed(s.fy, 2) << " px\n"
      << "  cx " << Fixed(k.cx, 2) << " ± " << Fixed(s.cx, 2) << "  cy " << Fixed(k.cy, 2) << " ± "
      << Fixed(s.cy, 2) << " px\n"
      << "  k1 " << Fixed(k.k1, 5) << " ± " << Fixed(s.k1, 5) << "  k2 " << Fixed(k.k2, 5) << " ± "
      << Fixed(s.k2, 5) << "\n"
      << "  RMS reprojection error " << Fixed(c.rms_px, 3) << " px, frame coverage "
      << Fixed(100 * c.coverage, 0) << " %\n";
  for (const geometry::PhotoCalibrationError& p : c.photos) {
    out << "  " << p.photo << ": " << p.corners << " corners, RMS " << Fixed(p.rms_px, 3)
        << " px, edge width " << Fixed(p.edge_width_px, 2) << " px\n";
  }
  return out.str();
}

LensCalibrationResult CalibrateLens(const std::vector<CalibrationPhoto>& photos,
                                    const LensCalibrationOptions& options) {
  options.Validate();
  if (static_cast<int>(photos.size()) < options.min_photos) {
    throw Error("lens calibration needs at least " + std::to_string(options.min_photos) +
                " photos of the board, got " + std::to_string(photos.size()));
  }
  LensCalibrationResult result;
  const cv::Size size = photos.front().image.size();
  for (const CalibrationPhoto& photo : photos) {
    if (photo.image.size() != size) {
      throw Error(photo.name + ": " + std::to_string(photo.image.cols) + "x" +
                  std::to_string(photo.image.rows) + ", but " + photos.front().name + " is " +
                  std::to_string(size.width) + "x" + std::to_string(size.height) +
                  ": one calibration is of one camera at one image size");
    }
    BoardDetection d = DetectBoard(photo.image, options.board, photo.name);
    if (static_cast<int>(d.corners.size()) < options.min_corners) {
      throw Error(photo.name + ": only " + std::to_string(d.corners.size()) +
                  " board corners found (" + std::to_string(d.markers) + " markers), at least " +
                  std::to_string(options.min_corners) +
                  " are needed: is the whole board in view, lit evenly, and is it the board "
                  "printed by `brdfrig target print` with these settings?");
    }
    if (d.edge_width_px > options.max_edge_width_px) {
      throw Error(photo.name + ": out of focus (edges " + Fixed(d.edge_width_px, 1) +
                  " px wide, at most " + Fixed(options.max_edge_width_px, 1) +
                  " allowed): refocus on the board or stop down, and retake it");
    }
    result.detections.push_back(std::move(d));
  }
  const double coverage =
      FrameCoverage(result.detections, size, options.coverage_columns, options.coverage_rows);
  if (coverage < options.min_coverage) {
    throw Error("the board's corners cover only " + Fixed(100 * coverage, 0) + " % of the frame (" +
                std::to_string(options.coverage_columns) + "x" +
                std::to_string(options.coverage_rows) + " cells), at least " +
                Fixed(100 * options.min_coverage, 0) +
                " % are needed to trust the distortion: add photos with the board near the "
                "edges and corners of the frame");
  }

  std::vector<cv::Mat> corners, ids;
  for (const BoardDetection& d : result.detections) {
    corners.push_back(cv::Mat(d.corners, true));
    ids.push_back(cv::Mat(d.ids, true));
  }
  cv::Mat camera_matrix, distortion, deviations, extrinsic_deviations, view_errors;
  std::vector<cv::Mat> rvecs, tvecs;
  const int flags = cv::CALIB_ZERO_TANGENT_DIST | cv::CALIB_FIX_K3;
  const double rms = cv::aruco::calibrateCameraCharuco(
      corners, ids, options.board.MakeBoard(), size, camera_matrix, distortion, rvecs, tvecs,
      deviations, extrinsic_deviations, view_errors, flags,
      cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 100, 1e-12));

  geometry::LensCalibration& c = result.calibration;
  c.created = NowUtcIso8601();
  c.software = std::string("brdfrig ") + BRDFRIG_VERSION;
  c.camera_model = options.camera_model;
  c.camera_serial = options.camera_serial;
  c.board = options.board.ToJson();
  c.settings = {{"model", "pinhole, radial k1 k2 (tangential and k3 held at 0)"},
                {"min_corners", options.min_corners},
                {"min_photos", options.min_photos},
                {"max_edge_width_px", options.max_edge_width_px},
                {"min_coverage", options.min_coverage},
                {"coverage_grid", {options.coverage_columns, options.coverage_rows}}};
  geometry::Intrinsics& k = c.intrinsics;
  k.width = size.width;
  k.height = size.height;
  k.fx = camera_matrix.at<double>(0, 0);
  k.fy = camera_matrix.at<double>(1, 1);
  k.cx = camera_matrix.at<double>(0, 2);
  k.cy = camera_matrix.at<double>(1, 2);
  k.k1 = distortion.at<double>(0);
  k.k2 = distortion.at<double>(1);
  // Standard deviations in OpenCV's order: fx, fy, cx, cy, k1, k2, p1, p2, k3, ...
  auto deviation = [&](int i) { return i < deviations.rows ? deviations.at<double>(i) : 0.0; };
  c.uncertainty.fx = deviation(0);
  c.uncertainty.fy = deviation(1);
  c.uncertainty.cx = deviation(2);
  c.uncertainty.cy = deviation(3);
  c.uncertainty.k1 = deviation(4);
  c.uncertainty.k2 = deviation(5);
  c.rms_px = rms;
  c.coverage = coverage;
  for (std::size_t i = 0; i < result.detections.size(); ++i) {
    const BoardDetection& d = result.detections[i];
    c.corners += static_cast<int>(d.corners.size());
    c.photos.push_back({d.photo, static_cast<int>(d.corners.size()),
                        view_errors.at<double>(static_cast<int>(i)), d.edge_width_px});
  }
  return result;
}

}  // namespace brdfrig::calibrate
