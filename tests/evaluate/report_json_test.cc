// report.json is the source: the text and HTML reports say what the json holds.
#include "evaluate/report_json.h"

#include <gtest/gtest.h>

#include <cmath>

#include "brdf/analytic.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "evaluate/material_report.h"

namespace brdfrig::evaluate {
namespace {

namespace fs = std::filesystem;

MaterialFigures Example() {
  const brdf::Ggx truth({brdf::Rgb(0.3, 0.1, 0.05), brdf::Rgb(0.9, 0.6, 0.35), 0.2});
  const brdf::Lambert fitted(brdf::Rgb(0.4, 0.2, 0.1));
  SphereTestOptions sphere;
  sphere.resolution = 32;
  sphere.keep_images = true;
  MaterialFigures f = JudgeBrdf(truth, fitted, sphere);
  for (double elevation : {20.0, 60.0}) {
    for (double phi : {0.0, 90.0}) {
      HeldOutResult r;
      r.view = {"v", phi * M_PI / 180, elevation * M_PI / 180, {}};
      r.whole_photo = {30 + elevation / 10, 0.01, 1, 100, "whole photo, 14-bit"};
      r.sample_only = {20 + phi / 10, 0.1, 1, 10, "sample only, 14-bit"};
      r.normalized_sample = {elevation == 20 ? INFINITY : 25.0, 0.05, 1, 10, "normalized"};
      r.relative_rmse = 0.25;
      r.relative_rmse_protocol = "relative";
      f.held_out.push_back(r);
    }
  }
  return f;
}

TEST(ReportJsonTest, EveryFigureIsInTheJsonWithItsProtocol) {
  const MaterialFigures f = Example();
  const nlohmann::json j = FiguresJson(f);
  ASSERT_EQ(j.at("held_out").at("views").size(), 4u);
  EXPECT_EQ(j["held_out"]["protocols"]["normalized_sample_psnr_db"], "normalized");
  EXPECT_EQ(j["held_out"]["views"][0]["normalized_sample_psnr_db"], "inf");
  EXPECT_DOUBLE_EQ(j["held_out"]["views"][3]["sample_only_psnr_db"].get<double>(), 29);
  ASSERT_EQ(j["held_out"]["by_elevation"].size(), 2u);
  EXPECT_DOUBLE_EQ(j["held_out"]["by_elevation"][1]["elevation_deg"].get<double>(), 60);
  EXPECT_DOUBLE_EQ(j["held_out"]["by_elevation"][1]["sample_only_psnr_db"].get<double>(), 24.5);
  EXPECT_EQ(j.at("sphere").at("lights").size(), 4u);
  EXPECT_NEAR(NumberFromJson(j["sphere"]["mean_psnr_db"]), f.sphere.mean_psnr_db, 1e-12);
  EXPECT_NE(j["sphere"]["protocol"].get<std::string>().find("sRGB"), std::string::npos);
  EXPECT_EQ(j.at("brdf").at("albedo").size(), 7u);
  EXPECT_NEAR(NumberFromJson(j["brdf"]["log_cosine_error"]), f.brdf.log_cosine_error, 1e-12);
  EXPECT_TRUE(std::isinf(NumberFromJson(nlohmann::json("inf"))));
  EXPECT_THROW(NumberFromJson(nlohmann::json("many")), Error);
}

TEST(ReportJsonTest, TextAndHtmlAreGeneratedFromTheJson) {
  const fs::path dir = fs::temp_directory_path() / "brdfrig_report_json";
  fs::remove_all(dir);
  const MaterialFigures f = Example();
  nlohmann::json report = NewReportJson("Example <report>");
  report["sections"].push_back(
      SectionJson({"Overview", {"a paragraph"}, {{"T", {"a"}, {{"1"}}}}, {}, {}}));
  report["figures"] = FiguresJson(f, dir);
  const WrittenReport written = WriteReport(dir, report);
  // Edit a figure in the json: the regenerated text follows the json, not the run.
  nlohmann::json reread = nlohmann::json::parse(ReadFileToString(written.json));
  EXPECT_EQ(reread, report);
  EXPECT_NE(written.text.find("Sphere test"), std::string::npos) << written.text;
  EXPECT_NE(written.text.find(Fixed(f.sphere.mean_psnr_db, 2)), std::string::npos);
  EXPECT_NE(written.text.find("a paragraph"), std::string::npos);
  EXPECT_NE(written.text.find("normalized sample"), std::string::npos);
  EXPECT_NE(written.text.find("Log-cosine error"), std::string::npos);
  EXPECT_NE(written.text.find("24.50"), std::string::npos);  // the 60° elevation's mean
  reread["figures"]["sphere"]["mean_psnr_db"] = 12.345;
  EXPECT_NE(ReportFromJson(reread).Text().find("12.35"), std::string::npos);
  const std::string html = ReadFileToString(written.html);
  EXPECT_NE(html.find("Example &lt;report&gt;"), std::string::npos);
  EXPECT_NE(html.find("spheres/light80_fit.png"), std::string::npos);
  EXPECT_TRUE(fs::exists(dir / "spheres" / "light80_fit.png"));
  EXPECT_NE(html.find("<svg"), std::string::npos);
  EXPECT_EQ(ReadFileToString(written.text_file), written.text);
}

TEST(ReportJsonTest, AnotherFormatIsRefused) {
  EXPECT_THROW(ReportFromJson(nlohmann::json{{"format", "something"}}), Error);
}

}  // namespace
}  // namespace brdfrig::evaluate
