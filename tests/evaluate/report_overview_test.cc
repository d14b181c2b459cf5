// The report opens with the material: the sphere images first, the plan's coverage with the
// figures coverage/ computes for that plan, the BRDF slices with the truth and the fit.
#include "evaluate/material_overview.h"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <regex>
#include <set>

#include "brdf/analytic.h"
#include "brdf/gltf_model.h"
#include "brdf/material_file.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "common/format.h"
#include "coverage/coverage.h"
#include "evaluate/coverage_report.h"
#include "evaluate/material_report.h"
#include "evaluate/report_json.h"
#include "evaluate/validation_photos.h"
#include "sim/scene.h"

namespace brdfrig::evaluate {
namespace {

namespace fs = std::filesystem;

// The analytic test scene with a written plan (no designer run): four fitted positions and a
// validation one.
sim::Scene TestScene() {
  std::string text = ReadFileToString(fs::path(BRDFRIG_SOURCE_DIR) / "sim/scenes/ggx.yaml");
  text = std::regex_replace(
      text, std::regex("positions: \\{design: [^\\n]*"),
      "positions: [{camera_arm: 20, light_arm: -20}, {camera_arm: 45, light_arm: -45}, "
      "{camera_arm: 30, light_arm: -55}, {camera_arm: 60, light_arm: -62}, "
      "{camera_arm: 40, light_arm: -30, validation: true}]");
  return sim::LoadSceneString(text, "ggx.yaml (test plan)",
                              fs::path(BRDFRIG_SOURCE_DIR) / "sim/scenes");
}

struct Written {
  nlohmann::json report;
  std::string html, text;
};

Written WriteExampleReport(const fs::path& dir, const sim::Scene& scene, const brdf::Brdf& fit) {
  fs::remove_all(dir);
  OverviewInputs in;
  in.models.truth = scene.sample.brdf.get();
  in.models.fit = &fit;
  in.models.fit_label = "fit (lambert)";
  in.models.gltf_note = "no glTF version in this test";
  in.plan =
      PlanGeometry{"the test plan", scene.rig, scene.capture.positions, scene.capture.validation};
  in.sphere.resolution = 48;
  in.sphere.keep_images = true;  // the sphere test's own images too, to compare
  in.plots.albedo_step_deg = 15;
  nlohmann::json report = NewReportJson("Overview test");
  report["sections"].push_back(SectionJson({"Overview", {"the job's own section"}, {}, {}, {}}));
  report["figures"] = FiguresJson(JudgeBrdf(*scene.sample.brdf, fit, in.sphere), dir);
  AddOverviewFigures(in, dir, &report["figures"]);
  const WrittenReport written = WriteReport(dir, report);
  return {nlohmann::json::parse(ReadFileToString(written.json)), ReadFileToString(written.html),
          written.text};
}

// The HTML between the n-th <h2> and the next one.
std::string HtmlSection(const std::string& html, int n) {
  std::size_t begin = 0;
  for (int i = 0; i <= n; ++i) {
    begin = html.find("<h2>", begin + 1);
    if (begin == std::string::npos) return "";
  }
  const std::size_t end = html.find("<h2>", begin + 1);
  return html.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
}

TEST(ReportOverviewTest, CoverageInTheReportIsWhatCoverageComputesForThePlan) {
  const sim::Scene scene = TestScene();
  const brdf::Lambert fit(brdf::Rgb(0.3, 0.2, 0.1));
  const Written w =
      WriteExampleReport(fs::temp_directory_path() / "brdfrig_overview_cov", scene, fit);
  const coverage::CoverageMap map =
      coverage::ComputeCoverage(scene.rig, scene.capture.positions, scene.capture.validation);
  ASSERT_GT(map.covered_fraction, 0);
  const nlohmann::json& c = w.report.at("figures").at("coverage");
  EXPECT_DOUBLE_EQ(c.at("covered_fraction").get<double>(), map.covered_fraction);
  EXPECT_DOUBLE_EQ(c.at("covered_fraction_with_validation").get<double>(),
                   map.covered_fraction_with_validation);
  ASSERT_EQ(c.at("positions").size(), 5u);
  // Each position's patch, and the fraction follows from the cells the json lists.
  std::set<int> fitted_cells;
  for (std::size_t i = 0; i < map.positions.size(); ++i) {
    const nlohmann::json& p = c["positions"][i];
    const coverage::PositionCoverage& m = map.positions[i];
    ASSERT_TRUE(p.at("observed").get<bool>()) << p.dump();
    EXPECT_EQ(p.at("validation").get<bool>(), i == 4);
    EXPECT_NEAR(p.at("theta_h_deg")[0].get<double>(), Degrees(m.theta_h_min), 1e-9);
    EXPECT_NEAR(p.at("theta_d_deg")[1].get<double>(), Degrees(m.theta_d_max), 1e-9);
    EXPECT_NEAR(p.at("theta_in_deg").get<double>(), Degrees(m.theta_in), 1e-9);
    EXPECT_NEAR(p.at("axes_deg").at("camera_arm").get<double>(),
                Degrees(scene.capture.positions[i].at("camera_arm")), 1e-9);
    EXPECT_EQ(p.at("cells").get<std::vector<int>>(), m.cells);
    if (!p.at("validation").get<bool>()) {
      for (int cell : p.at("cells")) fitted_cells.insert(cell);
    }
  }
  EXPECT_DOUBLE_EQ(static_cast<double>(fitted_cells.size()) / (32 * 32),
                   c["covered_fraction"].get<double>());
  // The HTML draws the map (coverage/'s SVG, its title with the fraction) and says the number.
  const std::string percent = Fixed(100 * map.covered_fraction, 1) + " %";
  EXPECT_NE(w.html.find("covered " + percent + "</text>"), std::string::npos);
  EXPECT_NE(w.text.find("Covered by the fitted positions: " + percent), std::string::npos);
  // The map drawn from the json is the one coverage/ draws from the plan.
  EXPECT_EQ(coverage::CoverageSvg(CoverageMapFromJson(c), "t"), coverage::CoverageSvg(map, "t"));
}

TEST(ReportOverviewTest, TheFirstSectionHoldsTheSphereImagesWithTheirPsnr) {
  const sim::Scene scene = TestScene();
  const brdf::Lambert fit(brdf::Rgb(0.3, 0.2, 0.1));
  const fs::path dir = fs::temp_directory_path() / "brdfrig_overview_spheres";
  const Written w = WriteExampleReport(dir, scene, fit);
  const std::string first = HtmlSection(w.html, 0);
  ASSERT_NE(first.find("<h2>The material</h2>"), std::string::npos) << first.substr(0, 200);
  const nlohmann::json& preview = w.report.at("figures").at("preview");
  const nlohmann::json& sphere = w.report["figures"].at("sphere");
  ASSERT_EQ(preview.at("rows").size(), 2u);  // truth, fit (no glTF version here)
  for (const std::string role : {"truth", "fit"}) {
    for (const std::string angle : {"0", "30", "60", "80"}) {
      const std::string file = "preview/" + role + "_light" + angle + ".png";
      EXPECT_NE(first.find("<img src='" + file + "'>"), std::string::npos) << file;
      const cv::Mat image = cv::imread((dir / file).string());
      ASSERT_EQ(image.rows, 48) << file;
    }
  }
  // The fit's PSNR under each light is the sphere test's, and is printed under its image.
  const nlohmann::json& fit_row = preview["rows"][1];
  for (std::size_t i = 0; i < 4; ++i) {
    const double psnr = NumberFromJson(fit_row.at("psnr_db")[i]);
    EXPECT_DOUBLE_EQ(psnr, NumberFromJson(sphere["lights"][i]["psnr_db"]));
    EXPECT_NE(first.find(Fixed(psnr, 2) + " dB</td>"), std::string::npos);
  }
  // The truth's images are the sphere test's truth (same scale, same pixels).
  const cv::Mat a = cv::imread((dir / "preview/truth_light30.png").string());
  const cv::Mat b = cv::imread((dir / "spheres/light30_truth.png").string());
  EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0);
  EXPECT_NE(first.find("no glTF version in this test"), std::string::npos);
  // Then the coverage and the curves, before the job's own section.
  EXPECT_NE(HtmlSection(w.html, 1).find("What the photos covered"), std::string::npos);
  EXPECT_NE(HtmlSection(w.html, 2).find("BRDF slices and albedo"), std::string::npos);
  EXPECT_NE(HtmlSection(w.html, 3).find("the job's own section"), std::string::npos);
}

TEST(ReportOverviewTest, TheSlicesPlotHoldsTheTruthAndTheFitSeries) {
  const sim::Scene scene = TestScene();
  const brdf::Lambert fit(brdf::Rgb(0.3, 0.2, 0.1));
  const Written w =
      WriteExampleReport(fs::temp_directory_path() / "brdfrig_overview_slices", scene, fit);
  const std::string plots = HtmlSection(w.html, 2);
  std::size_t slices = 0;
  for (std::size_t p = plots.find("In-plane BRDF, θi = "); p != std::string::npos;
       p = plots.find("In-plane BRDF, θi = ", p + 1)) {
    ++slices;
    const std::size_t end = plots.find("</svg>", p);
    const std::string svg = plots.substr(p, end - p);
    EXPECT_NE(svg.find("data-label='truth'"), std::string::npos);
    EXPECT_NE(svg.find("data-label='fit (lambert)'"), std::string::npos);
    EXPECT_NE(svg.find("<polyline"), std::string::npos);
  }
  EXPECT_EQ(slices, 5u);
  EXPECT_NE(plots.find("Directional albedo against incidence angle"), std::string::npos);
  // The json holds the curves the plots draw: the fit's in-plane values are a Lambert's ρ/π.
  const nlohmann::json& slice = w.report.at("figures").at("brdf_plots").at("slices")[0];
  for (const auto& v : slice.at("f").at("fit")) EXPECT_NEAR(v.get<double>(), 0.2 / M_PI, 1e-12);
}

TEST(ReportOverviewTest, TheGltfVersionIsARowOfItsOwnWithItsPsnr) {
  const sim::Scene scene = TestScene();
  brdf::Material material;
  material.kind = brdf::ModelKind::kGgx;
  std::string why;
  EXPECT_EQ(GltfVersionOf(material, &why), nullptr);
  EXPECT_NE(why.find("no gltf block"), std::string::npos) << why;
  brdf::GltfParams params;
  params.base_color = brdf::Rgb(0.5, 0.3, 0.1);
  params.roughness = 0.4;
  material.gltf = params;
  const std::shared_ptr<const brdf::Brdf> gltf = GltfVersionOf(material, &why);
  ASSERT_NE(gltf, nullptr);
  const brdf::Lambert fit(brdf::Rgb(0.3, 0.2, 0.1));
  const fs::path dir = fs::temp_directory_path() / "brdfrig_overview_gltf";
  fs::remove_all(dir);
  PreviewModels models{scene.sample.brdf.get(), &fit, "fit", gltf.get(), "", "material.glb"};
  SphereTestOptions sphere;
  sphere.resolution = 40;
  nlohmann::json report = NewReportJson("glTF row");
  report["figures"]["preview"] = MaterialPreviewJson(models, sphere, dir);
  const nlohmann::json& rows = report["figures"]["preview"]["rows"];
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[2].at("role"), "gltf");
  EXPECT_EQ(rows[2].at("against"), "truth");
  const SphereTestResult expected = SphereTest(*scene.sample.brdf, *gltf, sphere);
  EXPECT_DOUBLE_EQ(NumberFromJson(rows[2].at("mean_psnr_db")), expected.mean_psnr_db);
  const std::string html = ReadFileToString(WriteReport(dir, report).html);
  EXPECT_NE(html.find("<img src='preview/gltf_light60.png'>"), std::string::npos);
  EXPECT_NE(html.find("glTF 2.0 export: material.glb"), std::string::npos);
}

TEST(ReportOverviewTest, WithoutATruthTheFitIsBesideTheValidationPhotos) {
  const brdf::Lambert fit(brdf::Rgb(0.3, 0.2, 0.1));
  brdf::GltfParams params;
  params.roughness = 0.6;
  const brdf::GltfModel gltf(params);
  const fs::path dir = fs::temp_directory_path() / "brdfrig_overview_hardware";
  fs::remove_all(dir);
  SphereTestOptions sphere;
  sphere.resolution = 40;
  nlohmann::json report = NewReportJson("a hardware capture");
  report["figures"]["preview"] =
      MaterialPreviewJson({nullptr, &fit, "fit (ggx)", &gltf, "", ""}, sphere, dir);
  // One validation photo (a flat grey photo and a brighter prediction), as the job measures it.
  ValidationPhotoResult photo;
  photo.position = 5;
  photo.measured = true;
  photo.theta_in_deg = 41.5;
  photo.photo = cv::Mat(20, 20, CV_32FC3, cv::Scalar::all(0.2));
  photo.prediction = cv::Mat(20, 20, CV_32FC3, cv::Scalar::all(0.25));
  photo.figures = CompareSampleRadiance(photo.photo, photo.prediction,
                                        cv::Mat(20, 20, CV_8UC1, cv::Scalar(255)), "photo");
  report["figures"]["validation_photos"] = ValidationPhotosJson({photo}, "session", dir);
  const nlohmann::json& rows = report["figures"]["preview"]["rows"];
  ASSERT_EQ(rows.size(), 2u);  // the fit (no truth to compare with), its glTF version
  EXPECT_FALSE(rows[0].contains("psnr_db"));
  EXPECT_EQ(rows[1].at("against"), "fit");
  EXPECT_DOUBLE_EQ(NumberFromJson(rows[1].at("mean_psnr_db")),
                   SphereTest(fit, gltf, sphere).mean_psnr_db);
  const std::string html = ReadFileToString(WriteReport(dir, report).html);
  const std::string first = HtmlSection(html, 0);
  EXPECT_NE(first.find("<img src='preview/fit_light0.png'>"), std::string::npos);
  EXPECT_NE(first.find("<img src='validation/p5_photo.png'>"), std::string::npos);
  EXPECT_NE(first.find("<img src='validation/p5_render.png'>"), std::string::npos);
  EXPECT_NE(first.find("position 5 (θi 41.5°)"), std::string::npos);
  EXPECT_NE(first.find(Fixed(photo.figures.normalized_sample.psnr_db, 2) + " dB"),
            std::string::npos);
}

}  // namespace
}  // namespace brdfrig::evaluate
