#include "brdf/material_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "common/error.h"

namespace brdfrig::brdf {
namespace {

using ::testing::HasSubstr;

Material Example() {
  Material m;
  for (int k = 0; k < 3; ++k) {
    Slice s;
    s.theta_in = 0.2 + 0.3 * k;
    for (int c = 0; c < 3; ++c) s.channel[c] = {10.0 + k + c, 0.1, 0.02 + 0.001 * c, 0.05};
    m.slices.push_back(s);
    SliceDiagnostics d;
    d.residual = 0.01 * k;
    d.sample_count = 1000 + k;
    d.theta_min = 0;
    d.theta_max = 0.2;
    d.has_stddev = true;
    for (auto& ch : d.stddev) ch = {0.1, 0.001, NAN, 0.002};
    d.warnings = {k == 2 ? "A2 unobserved" : ""};
    m.diagnostics.push_back(d);
  }
  m.provenance = {{"software", "brdfrig test"}};
  return m;
}

std::string ErrorOf(const std::string& text) {
  try {
    ParseMaterial(text, "material.json");
  } catch (const FileError& e) {
    return e.what();
  }
  return "no error";
}

TEST(MaterialFileTest, RoundTripsExactlyThroughAFile) {
  const Material m = Example();
  const auto path = std::filesystem::temp_directory_path() / "brdfrig_material_test.json";
  WriteMaterialFile(path, m);
  const Material r = ReadMaterialFile(path);
  ASSERT_EQ(r.slices.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(r.slices[k].theta_in, m.slices[k].theta_in);
    EXPECT_EQ(r.slices[k].channel[2].h, m.slices[k].channel[2].h);
    EXPECT_EQ(r.diagnostics[k].sample_count, m.diagnostics[k].sample_count);
    EXPECT_TRUE(std::isnan(r.diagnostics[k].stddev[1][2]));
    EXPECT_EQ(r.diagnostics[k].stddev[1][3], 0.002);
  }
  EXPECT_EQ(r.provenance["software"], "brdfrig test");
  EXPECT_EQ(SerializeMaterial(r), SerializeMaterial(m));  // deterministic
  std::filesystem::remove(path);
}

TEST(MaterialFileTest, OutOfRangeValueNamesTheField) {
  nlohmann::json doc = nlohmann::json::parse(SerializeMaterial(Example()));
  doc["slices"][2]["green"]["h"] = -0.01;
  EXPECT_THAT(ErrorOf(doc.dump()),
              HasSubstr("material.json: slices[2].green.h: must be > 0, got -0.01"));
}

TEST(MaterialFileTest, MissingOrMistypedFieldsAreNamed) {
  nlohmann::json doc = nlohmann::json::parse(SerializeMaterial(Example()));
  doc["slices"][1]["red"].erase("x0");
  EXPECT_THAT(ErrorOf(doc.dump()), HasSubstr("slices[1].red.x0: missing"));
  doc = nlohmann::json::parse(SerializeMaterial(Example()));
  doc["slices"][0]["blue"]["A1"] = "big";
  EXPECT_THAT(ErrorOf(doc.dump()), HasSubstr("slices[0].blue.A1: expected a number"));
}

TEST(MaterialFileTest, TruncatedFileIsAParseErrorNotACrash) {
  const std::string text = SerializeMaterial(Example());
  for (std::size_t cut : {std::size_t{0}, std::size_t{10}, text.size() / 2, text.size() - 3}) {
    EXPECT_THAT(ErrorOf(text.substr(0, cut)), HasSubstr("material.json: not valid JSON"));
  }
}

// Issue 15, finding 6: 1e400 overflows a double; it was an internal error without the file.
TEST(MaterialFileTest, NumberOutOfRangeIsAFileErrorNamingTheFile) {
  std::string text = SerializeMaterial(Example());
  const std::size_t at = text.find("\"theta_in\": ") + 12;
  text.replace(at, text.find_first_of(",\n}", at) - at, "1e400");
  EXPECT_THAT(ErrorOf(text), HasSubstr("material.json: not valid JSON"));
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / "brdfrig_overflow_material.json";
  std::ofstream(file) << text;
  try {
    ReadMaterialFile(file);
    FAIL() << "1e400 was read";
  } catch (const FileError& e) {
    EXPECT_THAT(e.what(), HasSubstr(file.string()));
  }
}

TEST(MaterialFileTest, WrongFormatOrVersionIsRejected) {
  nlohmann::json doc = nlohmann::json::parse(SerializeMaterial(Example()));
  doc["version"] = 3;
  EXPECT_THAT(ErrorOf(doc.dump()), HasSubstr("version: this brdfrig reads version 2"));
  doc["format"] = "merl";
  EXPECT_THAT(ErrorOf(doc.dump()), HasSubstr("format: expected \"brdfrig-material\""));
  doc = nlohmann::json::parse(SerializeMaterial(Example()));
  doc["kind"] = "phong";
  EXPECT_THAT(ErrorOf(doc.dump()), HasSubstr("kind: unknown model kind 'phong'"));
}

TEST(MaterialFileTest, VersionOneSliceFilesStillLoadAsTheSeedKind) {
  nlohmann::json doc = nlohmann::json::parse(SerializeMaterial(Example()));
  doc["format"] = "brdfrig-slices";
  doc["version"] = 1;
  doc.erase("kind");
  doc.erase("fit");
  doc.erase("ladder");
  const Material m = ParseMaterial(doc.dump(), "old.json");
  EXPECT_EQ(m.kind, ModelKind::kSeed);
  ASSERT_EQ(m.slices.size(), 3u);
  EXPECT_EQ(m.slices[1].channel[0].a1, Example().slices[1].channel[0].a1);
}

Material MicrofacetExample() {
  Material m;
  m.kind = ModelKind::kMicrofacet;
  m.microfacet.distribution = Distribution::kTable;
  m.microfacet.diffuse = {0.1, 0.2, 0.3};
  m.microfacet.f0 = {0.9, 0.6, 0.4};
  m.microfacet.alpha = 0.15;
  m.microfacet.fresnel_knots = {0, 0.1, -0.2, 0.3};
  m.microfacet.log_d = {3, 2.5, 1, -1, -4};
  m.microfacet.max_theta_h = 0.6;
  m.microfacet.shadowing_alpha = 0.2;
  m.fit = {{"residual", 0.01}};
  m.ladder = nlohmann::json::array({{{"kind", "microfacet"}, {"score", 1.0}}});
  return m;
}

TEST(MaterialFileTest, MicrofacetKindsRoundTripExactly) {
  for (const Distribution d : {Distribution::kTable, Distribution::kGgx, Distribution::kBeckmann}) {
    Material m = MicrofacetExample();
    if (d != Distribution::kTable) {
      m.kind = d == Distribution::kGgx ? ModelKind::kGgx : ModelKind::kBeckmann;
      m.microfacet.distribution = d;
      m.microfacet.log_d.clear();
    }
    const Material r = ParseMaterial(SerializeMaterial(m), "m.json");
    EXPECT_EQ(r.kind, m.kind);
    EXPECT_EQ(r.microfacet.log_d, m.microfacet.log_d);
    EXPECT_EQ(r.microfacet.fresnel_knots, m.microfacet.fresnel_knots);
    EXPECT_EQ(r.microfacet.f0[2], m.microfacet.f0[2]);
    EXPECT_EQ(r.ladder, m.ladder);
    EXPECT_EQ(SerializeMaterial(r), SerializeMaterial(m));
    const Vec3 n = Vec3::UnitZ(), l = Vec3(0.3, 0, 1).normalized(),
               v = Vec3(-0.2, 0.1, 1).normalized();
    EXPECT_EQ(r.Model()->Eval(l, v, n)[1], m.Model()->Eval(l, v, n)[1]);
    EXPECT_THROW(r.Slices(), Error);
  }
}

TEST(MaterialFileTest, MicrofacetErrorsNameTheField) {
  nlohmann::json doc = nlohmann::json::parse(SerializeMaterial(MicrofacetExample()));
  doc["microfacet"]["log_d"][3] = 5;
  EXPECT_THAT(ErrorOf(doc.dump()), HasSubstr("microfacet: log_d[3] = 5; must be <= log_d[2]"));
  doc = nlohmann::json::parse(SerializeMaterial(MicrofacetExample()));
  doc["microfacet"]["f0"][1] = 1.5;
  EXPECT_THAT(ErrorOf(doc.dump()), HasSubstr("f0.green = 1.5; must be in [0, 1]"));
  doc = nlohmann::json::parse(SerializeMaterial(MicrofacetExample()));
  doc["microfacet"].erase("max_theta_h");
  EXPECT_THAT(ErrorOf(doc.dump()), HasSubstr("microfacet.max_theta_h: missing"));
}

TEST(MaterialFileTest, UnsortedKnotsAreRejected) {
  nlohmann::json doc = nlohmann::json::parse(SerializeMaterial(Example()));
  std::swap(doc["slices"][0], doc["slices"][1]);
  EXPECT_THAT(ErrorOf(doc.dump()), HasSubstr("slices[1].theta_in: must be greater"));
}

TEST(MaterialFileTest, WritingAnInvalidModelThrowsAndWritesNothing) {
  Material m = Example();
  m.slices[0].channel[0].a2 = -1;
  const auto path = std::filesystem::temp_directory_path() / "brdfrig_material_invalid.json";
  std::filesystem::remove(path);
  EXPECT_THROW(WriteMaterialFile(path, m), Error);
  EXPECT_FALSE(std::filesystem::exists(path));
}

// Issue 25, finding 6: the reader refuses what the renderer cannot draw (one limit each), so a
// file brdfrig reads is one every writer can use.
TEST(MaterialFileTest, RefusesWhatTheRendererRefuses) {
  nlohmann::json doc = nlohmann::json::parse(SerializeMaterial(MicrofacetExample()));
  doc["microfacet"]["fresnel_knots"] = std::vector<double>(kMaxFresnelKnots, 0.0);
  EXPECT_EQ(ErrorOf(doc.dump()), "no error");
  doc["microfacet"]["fresnel_knots"] = std::vector<double>(256, 0.0);
  EXPECT_THAT(ErrorOf(doc.dump()), HasSubstr("fresnel_knots.size = 256; must be <= 64"));
  // theta_in knots float cannot tell apart (the GPU spline divided by zero: a black sphere).
  doc = nlohmann::json::parse(SerializeMaterial(Example()));
  doc["slices"][1]["theta_in"] = doc["slices"][0]["theta_in"].get<double>() + 1e-9;
  EXPECT_THAT(ErrorOf(doc.dump()), HasSubstr("slices[1].theta_in: must be greater"));
  doc = nlohmann::json::parse(SerializeMaterial(Example()));
  for (int k = 3; k <= kMaxSlices; ++k) {
    nlohmann::json slice = doc["slices"][0];
    slice["theta_in"] = 0.8 + 0.01 * k;
    doc["slices"].push_back(slice);
  }
  EXPECT_THAT(ErrorOf(doc.dump()), HasSubstr("slices: at most 64 slices, got 65"));
}

// Issue 25, finding 11: a count beyond int was truncated silently.
TEST(MaterialFileTest, SampleCountBeyondIntIsRefused) {
  std::string text = SerializeMaterial(Example());
  const std::size_t at = text.find("\"sample_count\": ") + 16;
  text.replace(at, text.find_first_of(",\n}", at) - at, "99999999999");
  EXPECT_THAT(ErrorOf(text), HasSubstr("sample_count: expected a non-negative integer of at most"));
}

}  // namespace
}  // namespace brdfrig::brdf
