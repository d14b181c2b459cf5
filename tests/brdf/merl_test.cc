#include "brdf/merl.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <random>

#include "brdf/analytic.h"
#include "common/error.h"

namespace brdfrig::brdf {
namespace {

namespace fs = std::filesystem;

TEST(MerlTableTest, TabulatedAnalyticBrdfMatchesWithinTableResolution) {
  const Ggx ggx({Rgb(0.1, 0.2, 0.3), Rgb::Constant(0.04), 0.3});
  const MerlTable table = MerlTable::Tabulate(ggx);
  // Random directions: the lookup is nearest-bin, so the error is the BRDF's variation across
  // one bin; for this lobe the median error is well under 3 %, and no value is wildly off.
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<double> rel;
  for (int i = 0; i < 4000; ++i) {
    const double ti = std::acos(u(rng)) * 0.98, to = std::acos(u(rng)) * 0.98;
    const double po = 2 * M_PI * u(rng);
    const Vec3 l(std::sin(ti), 0, std::cos(ti));
    const Vec3 v(std::sin(to) * std::cos(po), std::sin(to) * std::sin(po), std::cos(to));
    const Rgb f = ggx.Eval(l, v, Vec3::UnitZ()), g = table.Eval(l, v, Vec3::UnitZ());
    rel.push_back(((f - g).abs() / f).maxCoeff());
  }
  std::sort(rel.begin(), rel.end());
  EXPECT_LT(rel[rel.size() / 2], 0.03);
  EXPECT_LT(rel[rel.size() * 9 / 10], 0.15);
}

TEST(MerlTableTest, WriteReadRoundTripIsBitExact) {
  const MerlTable table = MerlTable::Tabulate(Lambert(Rgb(0.5, 0.25, 0.125)));
  const fs::path path = fs::temp_directory_path() / "brdfrig_merl_test.binary";
  table.Write(path);
  EXPECT_EQ(fs::file_size(path), 34992012u);
  const MerlTable back = MerlTable::Read(path);
  EXPECT_EQ(back.data(), table.data());
  const Vec3 n = Vec3::UnitZ();
  EXPECT_NEAR(back.Eval(Vec3(0.3, 0, 1).normalized(), Vec3(-0.2, 0.1, 1).normalized(), n)[2],
              0.125 / M_PI, 1e-12);
  fs::remove(path);
}

TEST(MerlTableTest, WrongSizeFileGivesAClearError) {
  const fs::path path = fs::temp_directory_path() / "brdfrig_merl_short.binary";
  std::ofstream(path) << "not a table";
  try {
    MerlTable::Read(path);
    FAIL();
  } catch (const FileError& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("not a MERL table: expected 34992012 bytes"));
  }
  fs::remove(path);
}

}  // namespace
}  // namespace brdfrig::brdf
