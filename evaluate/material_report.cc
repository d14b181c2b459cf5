#include "evaluate/material_report.h"

#include <cmath>
#include <opencv2/imgcodecs.hpp>

#include "brdf/metrics.h"
#include "common/angles.h"
#include "evaluate/display_image.h"
#include "evaluate/svg_plot.h"

namespace brdfrig::evaluate {
namespace {}  // namespace

ReportSection HeldOutSection(const std::vector<HeldOutResult>& views, double elevation_deg,
                             const std::filesystem::path& report_dir) {
  std::filesystem::create_directories(report_dir / "views");
  ReportSection held{"Held-out views", {}, {}, {}, {}};
  held.paragraphs.push_back(
      "PSNR two ways. Whole photo: every pixel (paper and table included) in the capture's code "
      "values, peak = full scale, as the seed compared a real photo with a synthesized one. "
      "Sample only: the pixels inside the cut-out, same units: the honest figure for the "
      "material.");
  Table psnr{"Held-out PSNR (dB) at elevation " + Fixed(elevation_deg, 0) + "°",
             {"phi (deg)", "whole photo", "sample only"},
             {}};
  Series whole{"whole photo", {}, {}, true}, sample{"sample only", {}, {}, true};
  for (const HeldOutResult& v : views) {
    const double phi = Degrees(v.view.phi);
    psnr.rows.push_back(
        {Fixed(phi, 0), Fixed(v.whole_photo.psnr_db, 2), Fixed(v.sample_only.psnr_db, 2)});
    whole.x.push_back(phi);
    whole.y.push_back(v.whole_photo.psnr_db);
    sample.x.push_back(phi);
    sample.y.push_back(v.sample_only.psnr_db);
    const std::string stem = "views/phi" + std::to_string(static_cast<int>(std::lround(phi)));
    const double scale = AutoDisplayScale(v.photo);
    cv::imwrite((report_dir / (stem + "_photo.png")).string(), ToDisplay8(v.photo, scale));
    cv::imwrite((report_dir / (stem + "_render.png")).string(), ToDisplay8(v.rendering, scale));
    cv::imwrite((report_dir / (stem + "_diff.png")).string(),
                ToDisplay8(DifferenceImage(v.photo, v.rendering), scale));
    held.images.push_back({stem + "_photo.png", "phi " + Fixed(phi, 0) + "°: held-out photo"});
    held.images.push_back({stem + "_render.png", "rendering of the fitted model"});
    held.images.push_back({stem + "_diff.png", "|difference| (same scale)"});
  }
  held.tables.push_back(psnr);
  held.svg_plots.push_back(SvgLinePlot({whole, sample}, {"Held-out PSNR against orientation phi",
                                                         "phi (degrees)", "PSNR (dB)", 640, 400}));
  return held;
}

ReportSection BrdfSection(const brdf::Brdf& truth, const brdf::Brdf& fitted) {
  ReportSection brdf_section{"BRDF against the truth", {}, {}, {}, {}};
  brdf_section.paragraphs.push_back(
      "Log-cosine error (brdf::LogCosineError) of the fit against the "
      "simulated sample's BRDF: " +
      Fixed(brdf::LogCosineError(truth, fitted), 4));
  Table albedo{"Directional albedo (energy check; <= 1 conserves energy), green channel",
               {"theta_in (deg)", "truth", "fitted"},
               {}};
  for (double t : {15.0, 30.0, 45.0, 60.0}) {
    albedo.rows.push_back({Fixed(t, 0), Fixed(brdf::DirectionalAlbedo(truth, Radians(t))[1], 4),
                           Fixed(brdf::DirectionalAlbedo(fitted, Radians(t))[1], 4)});
  }
  brdf_section.tables.push_back(albedo);
  return brdf_section;
}

}  // namespace brdfrig::evaluate
