// The glTF export (brdf/gltf_file.h, reconstruct/gltf_export.h) in process: every model kind to
// .glb and .gltf, the container and the document read back and checked against what glTF 2.0
// requires of them (GLB header and chunks, accessors with bounds, aligned buffer views, unit
// normals), the provenance in extras, the tile's size, and the fit behind it.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "brdf/gltf_file.h"
#include "brdf/material_file.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "common/sha256.h"
#include "reconstruct/gltf_export.h"
#include "reconstruct/gltf_fit.h"
#include "tests/export/example_materials.h"

namespace brdfrig::reconstruct {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

fs::path Scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / "brdfrig_gltf_export" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::uint32_t U32(const std::string& bytes, std::size_t at) {
  std::uint32_t x = 0;
  std::memcpy(&x, bytes.data() + at, 4);
  return x;
}

struct Read {
  nlohmann::json json;
  std::string buffer;
};

// The GLB container as the specification lays it out (section 4.4).
Read ReadGlb(const fs::path& path) {
  const std::string bytes = ReadFileToString(path);
  Read out;
  EXPECT_GE(bytes.size(), 28u);
  EXPECT_EQ(U32(bytes, 0), 0x46546C67u);  // "glTF"
  EXPECT_EQ(U32(bytes, 4), 2u);
  EXPECT_EQ(U32(bytes, 8), bytes.size());
  const std::uint32_t json_length = U32(bytes, 12);
  EXPECT_EQ(U32(bytes, 16), 0x4E4F534Au);  // "JSON"
  EXPECT_EQ(json_length % 4, 0u);
  out.json = nlohmann::json::parse(bytes.substr(20, json_length));
  const std::size_t bin = 20 + json_length;
  const std::uint32_t bin_length = U32(bytes, bin);
  EXPECT_EQ(U32(bytes, bin + 4), 0x004E4942u);  // "BIN\0"
  EXPECT_EQ(bin_length % 4, 0u);
  EXPECT_EQ(bin + 8 + bin_length, bytes.size());
  out.buffer = bytes.substr(bin + 8, bin_length);
  return out;
}

// What glTF requires of the document, and what brdfrig promises in it.
void CheckDocument(const Read& file, const fs::path& material) {
  const nlohmann::json& doc = file.json;
  EXPECT_EQ(doc["asset"]["version"], "2.0");
  EXPECT_THAT(doc["asset"]["generator"].get<std::string>(), HasSubstr("brdfrig"));
  EXPECT_EQ(doc["extensionsUsed"], nlohmann::json({"KHR_materials_ior", "KHR_materials_specular"}));
  ASSERT_EQ(doc["materials"].size(), 1u);
  const nlohmann::json& m = doc["materials"][0];
  EXPECT_TRUE(m["extensions"].contains("KHR_materials_ior"));
  EXPECT_TRUE(m["extensions"].contains("KHR_materials_specular"));
  EXPECT_EQ(m["pbrMetallicRoughness"]["baseColorFactor"].size(), 4u);
  const nlohmann::json& extras = m["extras"]["brdfrig"];
  EXPECT_EQ(extras["source_sha256"], Sha256FileHex(material));
  EXPECT_TRUE(extras["gltf_fit"].is_object());
  EXPECT_EQ(doc["nodes"].size(), 2u);
  EXPECT_EQ(doc["scenes"][0]["nodes"], nlohmann::json({0, 1}));
  ASSERT_EQ(doc["buffers"].size(), 1u);
  EXPECT_EQ(doc["buffers"][0]["byteLength"].get<std::size_t>(), file.buffer.size());
  for (const nlohmann::json& view : doc["bufferViews"]) {
    EXPECT_EQ(view["byteOffset"].get<std::size_t>() % 4, 0u);
    EXPECT_LE(view["byteOffset"].get<std::size_t>() + view["byteLength"].get<std::size_t>(),
              file.buffer.size());
  }
  ASSERT_EQ(doc["meshes"].size(), 2u);
  for (const nlohmann::json& mesh : doc["meshes"]) {
    const nlohmann::json& attributes = mesh["primitives"][0]["attributes"];
    const nlohmann::json& position = doc["accessors"][attributes["POSITION"].get<int>()];
    EXPECT_EQ(position["min"].size(), 3u);
    EXPECT_EQ(position["max"].size(), 3u);
    // Normals are unit length (the validator's ACCESSOR_NON_UNIT check).
    const nlohmann::json& normal = doc["accessors"][attributes["NORMAL"].get<int>()];
    const nlohmann::json& view = doc["bufferViews"][normal["bufferView"].get<int>()];
    const auto* n =
        reinterpret_cast<const float*>(file.buffer.data() + view["byteOffset"].get<std::size_t>());
    for (int i = 0; i < normal["count"].get<int>(); ++i) {
      const double length = std::sqrt(n[3 * i] * n[3 * i] + n[3 * i + 1] * n[3 * i + 1] +
                                      n[3 * i + 2] * n[3 * i + 2]);
      ASSERT_NEAR(length, 1.0, 1e-5);
    }
  }
}

// The files, not the fit's accuracy (GltfFitTest's): a coarser grid and sphere keep the two
// exports of every kind cheap under the sanitizers.
GltfFitOptions QuickFit() {
  GltfFitOptions options;
  options.theta_h_steps = 12;
  options.theta_d_steps = 6;
  options.phi_d_steps = 4;
  options.sphere.resolution = 48;
  return options;
}

TEST(GltfExportTest, EveryKindExportsToGlbAndGltf) {
  const fs::path dir = Scratch("every_kind");
  for (brdf::ModelKind kind : brdf::kAllModelKinds) {
    SCOPED_TRACE(brdf::ModelKindName(kind));
    const fs::path material = dir / (std::string(brdf::ModelKindName(kind)) + ".json");
    brdf::WriteMaterialFile(material, testing::ExampleMaterial(kind));
    const fs::path glb = dir / (std::string(brdf::ModelKindName(kind)) + ".glb");
    const GltfExportSummary summary = ExportGltfFile(material, glb, QuickFit());
    // The examples carry no glTF version; a gltf material is its own.
    EXPECT_EQ(summary.fitted_now, kind != brdf::ModelKind::kGltf);
    CheckDocument(ReadGlb(glb), material);

    const fs::path gltf = dir / (std::string(brdf::ModelKindName(kind)) + ".gltf");
    (void)ExportGltfFile(material, gltf, QuickFit());
    Read text;
    text.json = nlohmann::json::parse(ReadFileToString(gltf));
    ASSERT_EQ(text.json["buffers"][0]["uri"], std::string(brdf::ModelKindName(kind)) + ".bin");
    text.buffer = ReadFileToString(dir / (std::string(brdf::ModelKindName(kind)) + ".bin"));
    CheckDocument(text, material);
    // Both files describe the same material.
    EXPECT_EQ(text.json["materials"], ReadGlb(glb).json["materials"]);
  }
}

TEST(GltfExportTest, TheTileHasTheCapturesCutOutSizeOrSaysItIsTheDefault) {
  const fs::path dir = Scratch("tile");
  brdf::Material m = testing::ExampleMaterial(brdf::ModelKind::kGgx);
  m.provenance["cutout_m"] = {0.08, 0.05};
  brdf::WriteMaterialFile(dir / "measured.json", m);
  (void)ExportGltfFile(dir / "measured.json", dir / "measured.glb");
  Read file = ReadGlb(dir / "measured.glb");
  const int tile = file.json["meshes"][1]["primitives"][0]["attributes"]["POSITION"];
  EXPECT_NEAR(file.json["accessors"][tile]["max"][0].get<double>(), 0.04, 1e-7);
  EXPECT_NEAR(file.json["accessors"][tile]["max"][2].get<double>(), 0.025, 1e-7);
  EXPECT_THAT(file.json["materials"][0]["extras"]["brdfrig"]["tile_size_source"].get<std::string>(),
              HasSubstr("provenance.cutout_m"));

  m.provenance.erase("cutout_m");
  brdf::WriteMaterialFile(dir / "plain.json", m);
  (void)ExportGltfFile(dir / "plain.json", dir / "plain.glb");
  file = ReadGlb(dir / "plain.glb");
  EXPECT_NEAR(file.json["accessors"][tile]["max"][0].get<double>(), 0.05, 1e-7);
  EXPECT_THAT(file.json["materials"][0]["extras"]["brdfrig"]["tile_size_source"].get<std::string>(),
              HasSubstr("default"));
}

TEST(GltfExportTest, AReconstructedGltfVersionIsExportedAsItIs) {
  const fs::path dir = Scratch("as_is");
  brdf::Material m = testing::ExampleMaterial(brdf::ModelKind::kGgx);
  AddGltfVersion(&m, GltfFitOptions{});
  brdf::WriteMaterialFile(dir / "m.json", m);
  const GltfExportSummary summary = ExportGltfFile(dir / "m.json", dir / "m.glb");
  EXPECT_FALSE(summary.fitted_now);
  const Read file = ReadGlb(dir / "m.glb");
  const nlohmann::json& material = file.json["materials"][0];
  EXPECT_DOUBLE_EQ(material["pbrMetallicRoughness"]["roughnessFactor"].get<double>(),
                   m.gltf->roughness);
  EXPECT_DOUBLE_EQ(material["extensions"]["KHR_materials_ior"]["ior"].get<double>(), m.gltf->ior);
  EXPECT_EQ(material["extras"]["brdfrig"]["gltf_fit"], m.gltf_fit);
}

TEST(GltfExportTest, WrongExtensionAndNonFiniteValuesWriteNothing) {
  const fs::path dir = Scratch("refused");
  brdf::WriteMaterialFile(dir / "m.json", testing::ExampleMaterial(brdf::ModelKind::kGgx));
  EXPECT_THROW((void)ExportGltfFile(dir / "m.json", dir / "m.obj"), FileError);
  brdf::GltfScene scene;
  scene.extras = {{"figure", std::nan("")}};
  try {
    brdf::WriteGltfFile(dir / "nan.glb", scene);
    ADD_FAILURE() << "a NaN in the extras was written";
  } catch (const FileError& e) {
    EXPECT_THAT(e.what(), HasSubstr("infinite or NaN"));
  }
  EXPECT_FALSE(fs::exists(dir / "nan.glb"));
  EXPECT_FALSE(fs::exists(dir / "m.obj"));
}

// Recover what was put in: the fit of a gltf material over the hemisphere gives its parameters
// back (f0 as written: ior from its largest channel, specularColor relative to it).
TEST(GltfFitTest, RecoversTheParametersOfAGltfMaterial) {
  brdf::GltfParams truth;
  truth.base_color = brdf::Rgb(0.5, 0.2, 0.1);
  truth.roughness = 0.35;
  truth.ior = 1.7;
  truth.specular = 0.8;
  truth.specular_color = brdf::Rgb(1.0, 0.9, 0.7);
  const GltfFitOptions options;
  const GltfFit fit = FitGltf(HemisphereSamples(brdf::GltfModel(truth), options), options);
  EXPECT_NEAR(fit.params.roughness, truth.roughness, 0.01);
  EXPECT_NEAR(fit.params.metallic, 0, 0.02);
  EXPECT_NEAR(fit.params.ior, truth.ior, 0.05);
  EXPECT_NEAR(fit.params.specular, truth.specular, 0.03);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(fit.params.base_color[c], truth.base_color[c], 0.01);
    EXPECT_NEAR(fit.params.specular_color[c], truth.specular_color[c], 0.03);
  }
  EXPECT_LT(fit.residual, 0.01);
}

TEST(GltfFitTest, EveryKindGetsAGltfVersionWithItsFigureAndIsCheap) {
  for (brdf::ModelKind kind : brdf::kLadderModelKinds) {
    SCOPED_TRACE(brdf::ModelKindName(kind));
    brdf::Material m = testing::ExampleMaterial(kind);
    const auto start = std::chrono::steady_clock::now();
    AddGltfVersion(&m, GltfFitOptions{});
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ASSERT_TRUE(m.gltf.has_value());
    const nlohmann::json& figure = m.gltf_fit["sphere_vs_model"];
    std::printf("%s: glTF version %.2f dB (worst %.2f dB) against the rung, %.2f s\n",
                brdf::ModelKindName(kind), figure["mean_psnr_db"].get<double>(),
                figure["worst_psnr_db"].get<double>(), seconds);
    // These examples are GGX-like lobes the glTF BRDF nearly holds.
    EXPECT_GT(figure["mean_psnr_db"].get<double>(), 30);
    EXPECT_EQ(m.gltf_fit["rung"], brdf::ModelKindName(kind));
    // Written and read back like any material.
    const brdf::Material r = brdf::ParseMaterial(brdf::SerializeMaterial(m), "m.json");
    EXPECT_EQ(r.gltf->roughness, m.gltf->roughness);
  }
}

}  // namespace
}  // namespace brdfrig::reconstruct
