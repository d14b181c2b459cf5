#include "evaluate/validation_photos.h"

#include <opencv2/imgcodecs.hpp>

#include "common/format.h"
#include "evaluate/display_image.h"
#include "evaluate/material_report.h"
#include "evaluate/sample_figures.h"

namespace brdfrig::evaluate {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string Cell(const json& value, int decimals) { return Fixed(NumberFromJson(value), decimals); }

}  // namespace

json ValidationPhotosJson(const std::vector<ValidationPhotoResult>& results,
                          const std::string& capture_name, const fs::path& report_dir) {
  json out = {{"capture", capture_name},
              {"method",
               "each photo measured like the reconstruction measures a position (HDR merge, "
               "cut-out pose, light from the highlight, paper radiometry); the material "
               "evaluated per sample pixel with that pixel's measured light and view directions "
               "and the paper's radiometric scale"},
              {"positions", json::array()}};
  std::vector<double> psnr;  // NaN where the photo is black over the sample
  double rmse_sum = 0;
  int measured = 0;
  for (const ValidationPhotoResult& r : results) {
    json j = {{"position", r.position}, {"measured", r.measured}};
    if (!r.measured) {
      j["error"] = r.error;
      out["positions"].push_back(j);
      continue;
    }
    if (!out.contains("protocols")) {
      out["protocols"] = {{"normalized_sample_psnr_db", r.figures.normalized_sample.protocol},
                          {"relative_rmse", r.figures.relative_rmse_protocol}};
    }
    j["theta_in_deg"] = r.theta_in_deg;
    j["light"] = r.light;
    j["normalized_sample_psnr_db"] = JsonNumber(r.figures.normalized_sample.psnr_db);
    j["relative_rmse"] = JsonNumber(r.figures.relative_rmse);
    j["photo_peak"] = JsonNumber(r.figures.peak);
    j["sample_pixels"] = r.figures.normalized_sample.pixels;
    if (!report_dir.empty() && !r.photo.empty()) {
      fs::create_directories(report_dir / "validation");
      const std::string stem = "validation/p" + std::to_string(r.position);
      const double scale = AutoDisplayScale(r.photo);
      cv::imwrite((report_dir / (stem + "_photo.png")).string(), ToDisplay8(r.photo, scale));
      cv::imwrite((report_dir / (stem + "_render.png")).string(), ToDisplay8(r.prediction, scale));
      cv::imwrite((report_dir / (stem + "_diff.png")).string(),
                  ToDisplay8(DifferenceImage(r.photo, r.prediction), scale));
      j["images"] = {{"photo", stem + "_photo.png"},
                     {"render", stem + "_render.png"},
                     {"diff", stem + "_diff.png"}};
    }
    psnr.push_back(r.figures.normalized_sample.psnr_db);
    rmse_sum += r.figures.relative_rmse;
    ++measured;
    out["positions"].push_back(j);
  }
  if (measured > 0) {
    out["mean_normalized_sample_psnr_db"] = JsonNumber(MeanOfDefined(psnr).mean);
    out["mean_relative_rmse"] = JsonNumber(rmse_sum / measured);
  }
  return out;
}

ReportSection ValidationPhotosSection(const json& v) {
  ReportSection s{"Validation photos", {}, {}, {}, {}};
  s.paragraphs.push_back("Photos of " + v.at("capture").get<std::string>() +
                         " left out of the fit against the material's prediction: " +
                         v.at("method").get<std::string>() + ".");
  if (v.contains("protocols")) {
    const json& p = v.at("protocols");
    s.paragraphs.push_back(
        "normalized sample PSNR: " + p.at("normalized_sample_psnr_db").get<std::string>() + ".");
    s.paragraphs.push_back("relative RMSE: " + p.at("relative_rmse").get<std::string>() + ".");
  }
  if (v.contains("mean_normalized_sample_psnr_db")) {
    s.paragraphs.push_back("Mean normalized sample PSNR " +
                           Cell(v.at("mean_normalized_sample_psnr_db"), 2) +
                           " dB; mean relative RMSE " + Cell(v.at("mean_relative_rmse"), 4) + ".");
  }
  Table t{"Validation photos",
          {"position", "theta_in (deg)", "light", "normalized sample PSNR (dB)", "relative RMSE",
           "sample pixels"},
          {}};
  for (const json& p : v.at("positions")) {
    const std::string position = std::to_string(p.at("position").get<int>());
    if (!p.at("measured").get<bool>()) {
      t.rows.push_back({position, "not measured: " + p.at("error").get<std::string>()});
      continue;
    }
    t.rows.push_back({position, Cell(p.at("theta_in_deg"), 2), p.at("light").get<std::string>(),
                      Cell(p.at("normalized_sample_psnr_db"), 2), Cell(p.at("relative_rmse"), 4),
                      std::to_string(p.at("sample_pixels").get<long>())});
    if (p.contains("images")) {
      const json& im = p.at("images");
      s.images.push_back(
          {im.at("photo").get<std::string>(), "position " + position + ": photo (HDR)"});
      s.images.push_back({im.at("render").get<std::string>(), "the material's prediction"});
      s.images.push_back({im.at("diff").get<std::string>(), "|difference| (same scale)"});
    }
  }
  s.tables.push_back(t);
  return s;
}

}  // namespace brdfrig::evaluate
