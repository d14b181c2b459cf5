// The `brdfrig` executable end to end on a small simulated capture: `reconstruct` prints the
// model ladder and `--model KIND` writes that kind; `evaluate --capture` compares the capture's
// validation photo with the material and says what is wrong with a bad position list.
#include <gtest/gtest.h>

#include "brdf/material_file.h"
#include "common/atomic_file.h"
#include "tests/common/run_brdfrig.h"
#include "tests/reconstruct/capture_fixture.h"

namespace brdfrig {
namespace {

namespace fs = std::filesystem;
using brdfrig::testing::RunBrdfrig;

class CliTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(fs::temp_directory_path() / "brdfrig_jobs_cli");
    reconstruct::testing::SceneSpec spec;
    spec.width = 320;
    spec.height = 240;
    spec.supersampling = 4;
    spec.positions =
        "[{camera_arm: 20, light_arm: -20}, {camera_arm: 40, light_arm: -40}, "
        "{camera_arm: 60, light_arm: -60}, {camera_arm: 35, light_arm: -35, validation: true}]";
    const brdf::Material truth = reconstruct::testing::FlatSliceTruth();
    (void)reconstruct::testing::SimulateCapture(*dir_, spec, &truth);
  }
  static void TearDownTestSuite() { delete dir_; }
  static std::string Capture() { return (*dir_ / "capture").string(); }
  static fs::path* dir_;
};
fs::path* CliTest::dir_ = nullptr;

TEST_F(CliTest, ReconstructPrintsTheLadderAndModelForcesOneKind) {
  const auto all = RunBrdfrig("reconstruct " + Capture() + " -o " +
                              (*dir_ / "all" / "material.json").string() + " --force");
  ASSERT_EQ(all.status, 0) << all.output;
  EXPECT_NE(all.output.find("model ladder"), std::string::npos) << all.output;
  for (brdf::ModelKind kind : brdf::kLadderModelKinds) {
    EXPECT_NE(all.output.find(std::string(brdf::ModelKindName(kind)) + ": "), std::string::npos)
        << brdf::ModelKindName(kind) << "\n"
        << all.output;
  }
  const brdf::Material chosen = brdf::ReadMaterialFile(*dir_ / "all" / "material.json");
  EXPECT_NE(all.output.find(std::string("* ") + brdf::ModelKindName(chosen.kind) + ": "),
            std::string::npos)
      << all.output;
  EXPECT_EQ(chosen.ladder.size(), std::size(brdf::kLadderModelKinds));

  const auto ggx = RunBrdfrig("reconstruct " + Capture() + " -o " +
                              (*dir_ / "ggx" / "material.json").string() + " --model ggx --force");
  ASSERT_EQ(ggx.status, 0) << ggx.output;
  EXPECT_NE(ggx.output.find("* ggx: "), std::string::npos) << ggx.output;
  EXPECT_EQ(ggx.output.find("beckmann: "), std::string::npos) << ggx.output;
  const brdf::Material forced = brdf::ReadMaterialFile(*dir_ / "ggx" / "material.json");
  EXPECT_EQ(forced.kind, brdf::ModelKind::kGgx);
  EXPECT_EQ(forced.ladder.size(), 1u);

  const auto bad = RunBrdfrig("reconstruct " + Capture() + " -o " +
                              (*dir_ / "bad" / "material.json").string() + " --model lambertian");
  EXPECT_NE(bad.status, 0) << bad.output;
  EXPECT_NE(bad.output.find("lambertian"), std::string::npos) << bad.output;
  EXPECT_NE(bad.output.find("microfacet"), std::string::npos) << "lists the kinds\n" << bad.output;
}

TEST_F(CliTest, EvaluateComparesTheValidationPhotos) {
  const std::string material = (*dir_ / "truth.json").string();
  const auto ok = RunBrdfrig("evaluate " + material + " --capture " + Capture() + " -o " +
                             (*dir_ / "report").string());
  ASSERT_EQ(ok.status, 0) << ok.output;
  EXPECT_NE(ok.output.find("Validation photos"), std::string::npos) << ok.output;
  EXPECT_TRUE(fs::exists(*dir_ / "report" / "validation" / "p3_photo.png"));

  const auto missing = RunBrdfrig("evaluate " + material + " --capture " + Capture() +
                                  " --positions 1,9 -o " + (*dir_ / "report9").string());
  EXPECT_EQ(missing.status, 1) << missing.output;
  EXPECT_NE(missing.output.find("position 9 is not in the capture (its positions: 0, 1, 2, 3)"),
            std::string::npos)
      << missing.output;

  const auto no_truth = RunBrdfrig("evaluate " + material + " -o " + (*dir_ / "r").string());
  EXPECT_EQ(no_truth.status, 1) << no_truth.output;
  EXPECT_NE(no_truth.output.find("--capture"), std::string::npos) << no_truth.output;
}

// Issue 25, finding 5: `demo -o FILE` ended in an internal error (an uncaught
// std::filesystem::filesystem_error, exit 2); it is the user's error, naming the path.
TEST(DemoCli, OutputThatIsAFileIsAnErrorNamingIt) {
  const fs::path file = fs::temp_directory_path() / "brdfrig_demo_output_is_a_file";
  WriteFileAtomically(file, std::string_view("not a directory"));
  const auto result = RunBrdfrig("demo -o " + file.string());
  EXPECT_EQ(result.status, 1) << result.output;
  EXPECT_NE(result.output.find(file.string()), std::string::npos) << result.output;
  EXPECT_EQ(result.output.find("internal error"), std::string::npos) << result.output;
  EXPECT_EQ(ReadFileToString(file), "not a directory");
}

// A seed material of two slices whose lobe peaks at `a1`: finite for the reader and the CPU.
fs::path HugeSlices(const std::string& name, double a1) {
  brdf::Material m;
  for (double theta_in : {0.3, 0.7}) {
    brdf::Slice s;
    s.theta_in = theta_in;
    for (auto& c : s.channel) c = {a1, 0.1, 0.03, 0.08};
    m.slices.push_back(s);
  }
  const fs::path file = fs::temp_directory_path() / name;
  brdf::WriteMaterialFile(file, m);
  return file;
}

// Issue 25, finding 6: A1 = 1e308 times MERL's scale (1500) is infinite: the export wrote a
// table of infinities (exit 0) that brdfrig itself then refused to read.
TEST(ExportCli, ATableWithInfiniteValuesIsRefusedNamingTheMaterial) {
  const fs::path material = HugeSlices("brdfrig_export_huge.json", 1e308);
  const fs::path out = fs::temp_directory_path() / "brdfrig_export_huge.binary";
  fs::remove(out);
  const auto result = RunBrdfrig("export " + material.string() + " -o " + out.string());
  EXPECT_EQ(result.status, 1) << result.output;
  EXPECT_NE(result.output.find(material.string() + ": its MERL table would hold"),
            std::string::npos)
      << result.output;
  EXPECT_FALSE(fs::exists(out));
}

// Issue 25, finding 6: A1 = 4e38 is beyond float: the GPU's image was NaN, written as a black
// sphere with exit 0.
TEST(RenderCli, ANonFiniteRenderingIsAnErrorNotABlackPicture) {
  const fs::path material = HugeSlices("brdfrig_render_huge.json", 4e38);
  const fs::path out = fs::temp_directory_path() / "brdfrig_render_huge.png";
  fs::remove(out);
  const auto result = RunBrdfrig("render " + material.string() +
                                 " --mesh sphere --width 64 --height 48 -o " + out.string());
  EXPECT_EQ(result.status, 1) << result.output;
  EXPECT_NE(result.output.find(material.string() + ": the render"), std::string::npos)
      << result.output;
  EXPECT_FALSE(fs::exists(out));
  // A sane material still renders.
  const auto sane = RunBrdfrig("render " + HugeSlices("brdfrig_render_sane.json", 20).string() +
                               " --mesh sphere --width 64 --height 48 -o " + out.string());
  EXPECT_EQ(sane.status, 0) << sane.output;
  EXPECT_TRUE(fs::exists(out));
}

}  // namespace
}  // namespace brdfrig
