// The demo's "Model ladder" section: every rung with its scores and the chosen flag, and the
// chosen rung's diagnostics; a small demo run writes it into report.json.
#include "jobs/ladder_section.h"

#include <gtest/gtest.h>

#include <regex>

#include "common/atomic_file.h"
#include "evaluate/report_json.h"
#include "jobs/demo.h"
#include "tests/reconstruct/capture_fixture.h"

namespace brdfrig::jobs {
namespace {

namespace fs = std::filesystem;

reconstruct::LadderResult ThreeRungs() {
  reconstruct::LadderResult ladder;
  reconstruct::RungResult seed;
  seed.kind = brdf::ModelKind::kSeed;
  seed.fitted = true;
  seed.material = reconstruct::testing::FlatSliceTruth();
  seed.score = 0.31;
  seed.fold_positions = {0, 1};
  seed.fold_scores = {0.3, 0.32};
  seed.validation_scores = {0.5};
  seed.size_bytes = 180;
  reconstruct::RungResult ggx;
  ggx.kind = brdf::ModelKind::kGgx;
  ggx.fitted = true;
  ggx.material.kind = brdf::ModelKind::kGgx;
  ggx.material.microfacet.alpha = 0.125;
  ggx.material.fit = {{"residual", 0.0123}, {"warnings", {"f0 barely constrained"}}};
  ggx.score = 0.12;
  ggx.fold_positions = {0, 1};
  ggx.fold_scores = {0.11, 0.13};
  ggx.validation_scores = {0.14};
  ggx.size_bytes = 96;
  ggx.chosen = true;
  reconstruct::RungResult beckmann;
  beckmann.kind = brdf::ModelKind::kBeckmann;
  beckmann.error = "too few samples";
  ladder.rungs = {seed, ggx, beckmann};
  ladder.chosen = 1;
  return ladder;
}

TEST(LadderSectionTest, ListsEveryRungWithItsScoresAndTheChosenOne) {
  const nlohmann::json section = evaluate::SectionJson(LadderSection(ThreeRungs()));
  EXPECT_EQ(section["title"], "Model ladder");
  const nlohmann::json& rungs = section["tables"][0];
  ASSERT_EQ(rungs["rows"].size(), 3u);
  const std::vector<std::string> header = rungs["header"];
  const auto column = [&](const std::string& name) {
    return std::find(header.begin(), header.end(), name) - header.begin();
  };
  const auto chosen = column("chosen");
  EXPECT_EQ(rungs["rows"][0][0], "seed");
  EXPECT_EQ(rungs["rows"][0][chosen], "no");
  EXPECT_EQ(rungs["rows"][1][0], "ggx");
  EXPECT_EQ(rungs["rows"][1][chosen], "yes");
  EXPECT_EQ(rungs["rows"][1][column("mean score")], "0.1200");
  EXPECT_EQ(rungs["rows"][1][column("LOPO folds")], "0.1100 0.1300");
  EXPECT_EQ(rungs["rows"][1][column("validation photos")], "0.1400");
  EXPECT_EQ(rungs["rows"][1][column("size (bytes)")], "96");
  EXPECT_NE(rungs["rows"][2][column("mean score")].get<std::string>().find("too few samples"),
            std::string::npos);
  // The chosen rung's diagnostics: its parameters, the fit's summary and warnings.
  const std::string text = section.dump();
  EXPECT_NE(text.find("0.1250"), std::string::npos) << "alpha";
  EXPECT_NE(text.find("0.0123"), std::string::npos) << "fit residual";
  EXPECT_NE(text.find("f0 barely constrained"), std::string::npos);
  EXPECT_NE(text.find("the ggx rung"), std::string::npos);
  EXPECT_EQ(text.find("seed's slice model)"), text.find("the seed rung"))
      << "no claim that the seed's slices were written";
}

TEST(LadderSectionTest, AChosenSliceRungShowsItsSlices) {
  reconstruct::LadderResult ladder = ThreeRungs();
  ladder.rungs[1].chosen = false;
  ladder.rungs[0].chosen = true;
  ladder.chosen = 0;
  const evaluate::ReportSection s = LadderSection(ladder);
  ASSERT_EQ(s.tables.size(), 2u);
  EXPECT_NE(s.tables[1].caption.find("slices"), std::string::npos);
  EXPECT_EQ(s.tables[1].rows.size(), 1u);
  EXPECT_NE(ChosenModelPhrase(ladder).find("the seed rung (the seed's slice model)"),
            std::string::npos);
}

// The demo at 320×240 with a designed plan of four positions plus one validation position:
// report.json has the ladder section with every rung, and the validation photo comparison.
TEST(LadderSectionTest, SmallDemoReportsTheLadderAndTheValidationPhoto) {
  const fs::path dir = fs::temp_directory_path() / "brdfrig_demo_ladder";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::string scene = ReadFileToString(fs::path(BRDFRIG_SOURCE_DIR) / "sim/scenes/ggx.yaml");
  scene = std::regex_replace(scene, std::regex("resolution: \\[1600, 1200\\]"),
                             "resolution: [320, 240]");
  scene = std::regex_replace(
      scene, std::regex("positions: \\{design: \\{count: 6, objective: coverage\\}\\}"),
      "positions: {design: {count: 4, validation: 1, objective: coverage}}");
  ASSERT_NE(scene.find("validation: 1"), std::string::npos) << "the default scene changed";
  WriteFileAtomically(dir / "scene.yaml", scene);
  DemoOptions options;
  options.scene = dir / "scene.yaml";
  options.output_dir = dir / "out";
  options.view_elevations_deg = {40};
  options.view_phis_deg = {0};
  const DemoSummary summary = RunDemo(options);
  const nlohmann::json report = nlohmann::json::parse(ReadFileToString(summary.report_json));
  const nlohmann::json* ladder = nullptr;
  for (const nlohmann::json& s : report["sections"]) {
    if (s["title"] == "Model ladder") ladder = &s;
  }
  ASSERT_NE(ladder, nullptr);
  const nlohmann::json& rows = (*ladder)["tables"][0]["rows"];
  EXPECT_EQ(rows.size(), std::size(brdf::kLadderModelKinds));
  int chosen = 0;
  for (const nlohmann::json& row : rows) chosen += row.back() == "yes";
  EXPECT_EQ(chosen, 1);
  const brdf::Material material = brdf::ReadMaterialFile(dir / "out" / "material.json");
  EXPECT_NE(summary.text.find(std::string("reconstructed into the ") +
                              brdf::ModelKindName(material.kind) + " rung"),
            std::string::npos);
  const nlohmann::json& photos = report["figures"].at("validation_photos");
  ASSERT_EQ(photos["positions"].size(), 1u);
  std::printf(
      "demo: chosen %s, validation photo normalized PSNR %s dB\n",
      brdf::ModelKindName(material.kind),
      photos["positions"][0].value("normalized_sample_psnr_db", nlohmann::json()).dump().c_str());
  EXPECT_TRUE(photos["positions"][0]["measured"].get<bool>());
}

}  // namespace
}  // namespace brdfrig::jobs
