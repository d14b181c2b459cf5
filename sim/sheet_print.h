// A printed sheet as the simulator sees it: the sheet's ink coverage sampled finely (the same
// drawing `brdfrig target print` writes, calibrate/target_sheets.h), on Lambertian paper with
// Lambertian toner. The scene board's ChArUco page and the rig's marker mask are both one.
#pragma once

#include <opencv2/core.hpp>

#include "geometry/rig_geometry.h"

namespace brdfrig::sim {

// 20 samples per millimetre: a tenth of a pixel of the default camera at 0.4 m, so a print is
// as sharp to the camera as a laser print, and edges land at their exact positions.
inline constexpr double kPrintPxPerM = 20000;

// Toner black's diffuse reflectance.
inline constexpr double kTonerAlbedo = 0.04;

class SheetPrint {
 public:
  // `ink`: CV_8U coverage (255 = ink) of a page of width_m × height_m; sample (u, v) covers
  // page coordinates [u, u + 1) / px_per_m from the page's top-left.
  SheetPrint(cv::Mat ink, double px_per_m, double width_m, double height_m, double paper_albedo,
             double ink_albedo);

  // Albedo at a point of the page (metres from its top-left, x along, y down).
  double Albedo(double x, double y) const;
  // Whether ink covers most of that point (for the anti-aliasing of edges).
  bool Ink(double x, double y) const;
  bool OnPage(double x, double y) const {
    return x >= 0 && y >= 0 && x <= width_m_ && y <= height_m_;
  }

 private:
  double Coverage(double x, double y) const;
  cv::Mat ink_;
  double px_per_m_;
  double width_m_, height_m_;
  double paper_, ink_albedo_;
};

// The marker mask of a target whose `markers` are set: the mask sheet (markers, cut line, scale
// bar; no text) on paper of the target's albedo. Its page's top-left is the paper's corner at
// world (-paper_width / 2, +paper_height / 2), page y running along world -y.
SheetPrint PrintOfMask(const geometry::TargetGeometry& target);

}  // namespace brdfrig::sim
