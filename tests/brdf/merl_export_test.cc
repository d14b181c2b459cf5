// `brdfrig export` for the model ladder's microfacet kinds: material.json → MERL .binary → read
// back holds the model's own values at every bin centre (the table samples, it does not fit).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>

#include "brdf/brdf_file.h"
#include "brdf/material_file.h"
#include "brdf/merl.h"
#include "brdf/microfacet_terms.h"
#include "common/error.h"

namespace brdfrig::brdf {
namespace {

constexpr double kScale[3] = {1.0 / 1500.0, 1.15 / 1500.0, 1.66 / 1500.0};  // MERL's

Material TableMaterial() {
  Material m;
  m.kind = ModelKind::kMicrofacet;
  MicrofacetModelParams& p = m.microfacet;
  p.distribution = Distribution::kTable;
  p.diffuse = Rgb(0.2, 0.1, 0.05);
  p.f0 = Rgb(0.5, 0.4, 0.3);
  p.alpha = 0.2;
  p.shadowing_alpha = 0.15;
  p.max_theta_h = 0.5;
  p.fresnel_knots = {0, 0.1, -0.1};
  for (int k = 0; k < 16; ++k) {
    p.log_d.push_back(
        microfacet::LogGgxD(std::cos(microfacet::TableKnotThetaH(k, 16, p.max_theta_h)), 0.1));
  }
  return m;
}

// Light and view directions (normal +z) at the centre of MERL bin (ih, id, ip): the half vector
// at theta_h in the xz plane, the difference vector at (theta_d, phi_d) around it.
void BinCentre(int ih, int id, int ip, Vec3* l, Vec3* v) {
  const double u = (ih + 0.5) / kMerlThetaH, theta_h = u * u * M_PI / 2;
  const double theta_d = (id + 0.5) / kMerlThetaD * M_PI / 2, phi_d = (ip + 0.5) / kMerlPhiD * M_PI;
  const Vec3 d(std::sin(theta_d) * std::cos(phi_d), std::sin(theta_d) * std::sin(phi_d),
               std::cos(theta_d));
  const Eigen::AngleAxisd tilt(theta_h, Vec3::UnitY());
  *l = tilt * d;
  *v = tilt * Vec3(-d.x(), -d.y(), d.z());
}

TEST(MerlExportTest, MicrofacetMaterialExportsAndReadsBackWithItsValuesAtBinCentres) {
  const auto dir = std::filesystem::temp_directory_path() / "brdfrig_merl_export_test";
  std::filesystem::create_directories(dir);
  for (ModelKind kind : {ModelKind::kMicrofacet, ModelKind::kGgx, ModelKind::kBeckmann}) {
    SCOPED_TRACE(ModelKindName(kind));
    Material material = TableMaterial();
    if (kind != ModelKind::kMicrofacet) {
      material.kind = kind;
      material.microfacet.distribution =
          kind == ModelKind::kGgx ? Distribution::kGgx : Distribution::kBeckmann;
      material.microfacet.log_d.clear();
    }
    WriteMaterialFile(dir / "material.json", material);
    ExportMerlFile(dir / "material.json", dir / "material.binary");
    const MerlTable table = MerlTable::Read(dir / "material.binary");
    const MicrofacetModel model(material.microfacet);
    int checked = 0, below_horizon = 0;
    double worst_stored = 0, worst_lookup = 0;
    for (int ih = 0; ih < kMerlThetaH; ih += 3) {
      for (int id = 0; id < kMerlThetaD; id += 3) {
        for (int ip = 0; ip < kMerlPhiD; ip += 7) {
          Vec3 l, v;
          BinCentre(ih, id, ip, &l, &v);
          const std::size_t index = ip + kMerlPhiD * (id + kMerlThetaD * ih);
          if (l.z() <= 0 || v.z() <= 0) {
            ++below_horizon;  // "no data" bins hold negative values
            for (int c = 0; c < 3; ++c) EXPECT_LT(table.data()[c * kMerlBins + index], 0);
            continue;
          }
          const Rgb f = model.Eval(l, v, Vec3::UnitZ());
          const Rgb looked_up = table.Eval(l, v, Vec3::UnitZ());
          for (int c = 0; c < 3; ++c) {
            const double stored = table.data()[c * kMerlBins + index] * kScale[c];
            worst_stored = std::max(worst_stored, std::abs(stored - f[c]) / f[c]);
            worst_lookup = std::max(worst_lookup, std::abs(looked_up[c] - f[c]) / f[c]);
          }
          ++checked;
        }
      }
    }
    EXPECT_GT(checked, 10000);
    EXPECT_GT(below_horizon, 0);
    EXPECT_LT(worst_stored, 1e-12);  // doubles written and read bit for bit
    EXPECT_LT(worst_lookup, 1e-12);  // a bin centre looks up its own bin
  }
  std::filesystem::remove_all(dir);
}

TEST(MerlExportTest, OutputMustBeABinaryFile) {
  EXPECT_THROW(ExportMerlFile("material.json", "material.exr"), FileError);
}

}  // namespace
}  // namespace brdfrig::brdf
