// What real consumers draw of fitted materials' glTF versions: each material.json is exported
// by the real `brdfrig export` to .glb, the file's sphere is rendered in the consumer scene
// (tests/consumers/consumer_scene.h) by three.js in headless Chromium (both pictures: the glTF
// BRDF with three.js's two added terms taken out, and three.js as shipped) and by Blender's
// importer + Cycles, and each picture is compared with brdfrig's own render of the parameters
// the file holds (PSNR in linear radiance over the sphere's interior, the tests' protocol).
//   bench_gltf_consumers [--samples N] [--keep DIR] MATERIAL.json...
// Prints a markdown table. Exit status 1 when a consumer is missing or a material fails (the
// table says which): a partial table is not a result.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "brdf/gltf_model.h"
#include "brdf/material_file.h"
#include "common/error.h"
#include "common/exr_io.h"
#include "common/format.h"
#include "tests/common/run_brdfrig.h"
#include "tests/consumers/consumer_scene.h"

namespace {

using namespace brdfrig;
namespace fs = std::filesystem;

struct Command {
  int status = -1;
  std::string output;
};

Command Run(const std::string& command) {
  Command result;
  FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  if (pipe == nullptr) return result;
  char buffer[4096];
  while (size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) result.output.append(buffer, n);
  result.status = ::pclose(pipe);
  return result;
}

std::string Quoted(const fs::path& path) { return "'" + path.string() + "'"; }

std::string ReadAll(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw FileError(path.string(), "cannot read");
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The material the .glb holds (its JSON chunk), read back as a consumer reads it: brdfrig's side
// renders these numbers, not the material.json's, so the figure is the consumer's alone.
brdf::GltfParams ParamsInGlb(const fs::path& glb) {
  const std::string bytes = ReadAll(glb);
  if (bytes.size() < 20 || bytes.compare(0, 4, "glTF") != 0 || bytes.compare(16, 4, "JSON") != 0) {
    throw FileError(glb.string(), "not a GLB with a JSON chunk");
  }
  std::uint32_t length = 0;
  std::memcpy(&length, bytes.data() + 12, 4);
  const nlohmann::json doc = nlohmann::json::parse(bytes.substr(20, length));
  const nlohmann::json& m = doc.at("materials").at(0);
  const nlohmann::json& pbr = m.at("pbrMetallicRoughness");
  const nlohmann::json none = nlohmann::json::object();
  const nlohmann::json& ext = m.contains("extensions") ? m.at("extensions") : none;
  const nlohmann::json& ior = ext.contains("KHR_materials_ior") ? ext["KHR_materials_ior"] : none;
  const nlohmann::json& spec =
      ext.contains("KHR_materials_specular") ? ext["KHR_materials_specular"] : none;
  brdf::GltfParams p;  // the specification's defaults where the file says nothing
  const std::vector<double> color = pbr.value("baseColorFactor", std::vector<double>{1, 1, 1, 1});
  const std::vector<double> specular_color =
      spec.value("specularColorFactor", std::vector<double>{1, 1, 1});
  for (int i = 0; i < 3; ++i) {
    p.base_color[i] = color.at(i);
    p.specular_color[i] = specular_color.at(i);
  }
  p.metallic = pbr.value("metallicFactor", 1.0);
  p.roughness = pbr.value("roughnessFactor", 1.0);
  p.ior = ior.value("ior", 1.5);
  p.specular = spec.value("specularFactor", 1.0);
  return p;
}

double MaxDeviation(const nlohmann::json& three, const brdf::GltfParams& p) {
  double d = 0;
  for (int i = 0; i < 3; ++i) {
    d = std::max(d, std::abs(three.at("color")[i].get<double>() - p.base_color[i]));
    d = std::max(d, std::abs(three.at("specularColor")[i].get<double>() - p.specular_color[i]));
  }
  d = std::max(d, std::abs(three.at("metalness").get<double>() - p.metallic));
  d = std::max(d, std::abs(three.at("roughness").get<double>() - p.roughness));
  d = std::max(d, std::abs(three.at("ior").get<double>() - p.ior));
  return std::max(d, std::abs(three.at("specularIntensity").get<double>() - p.specular));
}

struct Row {
  std::string name, kind, params, failure;
  double three_spec_db = NAN, three_shipped_db = NAN, cycles_db = NAN;
  double three_read_deviation = NAN, blender_read_deviation = NAN;
  double seconds = 0;
};

Row Measure(const fs::path& material_json, const fs::path& dir, int samples) {
  const auto start = std::chrono::steady_clock::now();
  Row row;
  row.name = material_json.stem().string();
  row.kind = brdf::ModelKindName(brdf::ReadMaterialFile(material_json).kind);
  const testing::ConsumerView view;
  const fs::path glb = dir / (row.name + ".glb");
  const testing::CommandResult exported =
      testing::RunBrdfrig("export " + Quoted(material_json) + " -o " + Quoted(glb));
  if (exported.status != 0) {
    row.failure = "brdfrig export: " + exported.output;
    return row;
  }
  const brdf::GltfParams p = ParamsInGlb(glb);
  row.params = "(" + Fixed(p.base_color[0], 3) + ", " + Fixed(p.base_color[1], 3) + ", " +
               Fixed(p.base_color[2], 3) + "); " + Fixed(p.metallic, 2) + "; " +
               Fixed(p.roughness, 3) + "; " + Fixed(p.ior, 2) + "; " + Fixed(p.specular, 2);
  const cv::Mat ours = testing::RenderWithBrdfrig(brdf::GltfModel(p), view);
  const cv::Mat mask = testing::SphereInterior(view);

  const fs::path three_json = dir / (row.name + ".three.json");
  const Command three = Run("bash " + Quoted(testing::ConsumersDir() / "three_render.sh") + " " +
                            Quoted(glb) + " " + Quoted(three_json) + " '" + view.Query() + "'");
  if (three.status != 0) {
    row.failure += "three.js: " + three.output + " ";
  } else {
    const nlohmann::json t = nlohmann::json::parse(ReadAll(three_json));
    row.three_read_deviation = MaxDeviation(t.at("material"), p);
    row.three_spec_db =
        testing::CompareLinear(ours, testing::ThreeJsImage(t, "spec"), mask).psnr_db;
    row.three_shipped_db =
        testing::CompareLinear(ours, testing::ThreeJsImage(t, "shipped"), mask).psnr_db;
  }

  const fs::path report = dir / (row.name + ".blender.json"), exr = dir / (row.name + ".exr");
  const Command blender =
      Run("blender -b --factory-startup --python " +
          Quoted(testing::ConsumersDir() / "blender_check.py") + " -- " + Quoted(glb) + " " +
          Quoted(report) + " " + Quoted(exr) + " " + testing::BlenderViewArguments(view, samples));
  if (blender.status != 0 || !fs::exists(report) ||
      blender.output.find("Traceback") != std::string::npos) {
    row.failure +=
        "blender: " +
        blender.output.substr(blender.output.size() > 2000 ? blender.output.size() - 2000 : 0);
  } else {
    const nlohmann::json b = nlohmann::json::parse(ReadAll(report));
    const nlohmann::json& principled = b.at("materials").begin().value();
    double d = 0;
    for (int i = 0; i < 3; ++i) {
      d = std::max(d, std::abs(principled.at("Base Color")[i].get<double>() - p.base_color[i]));
    }
    d = std::max(d, std::abs(principled.at("Metallic").get<double>() - p.metallic));
    d = std::max(d, std::abs(principled.at("Roughness").get<double>() - p.roughness));
    row.blender_read_deviation = std::max(d, std::abs(principled.at("IOR").get<double>() - p.ior));
    row.cycles_db = testing::CompareLinear(ours, ReadRadianceExr(exr), mask).psnr_db;
  }
  row.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return row;
}

}  // namespace

int main(int argc, char** argv) {
  int samples = 64;  // Cycles samples per pixel, as tests/consumers/blender_test.cc
  fs::path keep;
  std::vector<fs::path> materials;
  std::string command = "bench_gltf_consumers";
  for (int i = 1; i < argc; ++i) command += std::string(" ") + argv[i];
  try {
    for (int i = 1; i < argc; ++i) {
      const bool more = i + 1 < argc;
      if (std::strcmp(argv[i], "--samples") == 0 && more) {
        samples = std::stoi(argv[++i]);
      } else if (std::strcmp(argv[i], "--keep") == 0 && more) {
        keep = argv[++i];
      } else if (argv[i][0] == '-') {
        throw OptionsError(std::string("unknown option ") + argv[i]);
      } else {
        materials.push_back(argv[i]);
      }
    }
    if (materials.empty()) throw OptionsError("no material.json given");
    std::vector<std::string> missing;
    for (const char* program : {"node", "chromium", "blender"}) {
      if (!testing::HaveProgram(program)) missing.push_back(program);
    }
    if (!fs::exists(testing::ConsumersDir() / "node_modules" / "three")) {
      missing.push_back("three.js (npm ci in tests/consumers)");
    }
    if (!missing.empty()) {
      std::string list;
      for (const auto& m : missing) list += " " + m;
      std::fprintf(stderr, "bench_gltf_consumers: missing%s (scripts/setup.sh)\n", list.c_str());
      return 1;
    }
    const fs::path dir = keep.empty() ? fs::temp_directory_path() / "brdfrig_gltf_consumers" : keep;
    fs::create_directories(dir);
    const testing::ConsumerView view;
    std::printf(
        "Command: `%s`. Consumer scene of tests/consumers/consumer_scene.h (%d x %d px, one "
        "directional light, linear radiance); PSNR against brdfrig's render of the numbers the "
        ".glb holds, over the sphere's interior (view cosine >= 0.15), peak = brdfrig's 99th "
        "percentile. Cycles: %d samples, direct light only. Read back: the largest |difference| "
        "between the file's numbers and the consumer's material (three.js: colour, metalness, "
        "roughness, ior, specularIntensity, specularColor; Blender: Base Color, Metallic, "
        "Roughness, IOR).\n\n",
        command.c_str(), view.width, view.height, samples);
    std::printf(
        "| material | rung | glTF version: baseColor; metallic; roughness; ior; specular | "
        "three.js, glTF BRDF (dB) | three.js as shipped (dB) | Blender Cycles (dB) | read back: "
        "three.js / Blender | time (s) |\n|---|---|---|---|---|---|---|---|\n");
    std::fflush(stdout);
    bool failed = false;
    for (const fs::path& m : materials) {
      Row r;
      try {
        r = Measure(m, dir, samples);
      } catch (const std::exception& e) {
        r.name = m.stem().string();
        r.failure = e.what();
      }
      std::printf("| %s | %s | %s | %s | %s | %s | %.1e / %.1e | %.0f |\n", r.name.c_str(),
                  r.kind.c_str(), r.params.c_str(), Fixed(r.three_spec_db, 1).c_str(),
                  Fixed(r.three_shipped_db, 1).c_str(), Fixed(r.cycles_db, 1).c_str(),
                  r.three_read_deviation, r.blender_read_deviation, r.seconds);
      if (!r.failure.empty()) {
        std::printf("\n%s failed: %s\n\n", r.name.c_str(), r.failure.c_str());
        failed = true;
      }
      std::fflush(stdout);
    }
    return failed ? 1 : 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_gltf_consumers: %s\n", e.what());
    return 1;
  }
}
