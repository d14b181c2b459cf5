// Which source the glTF version is fitted to (reconstruct/gltf_fit.h, docs/gltf.md): the chosen
// rung over the whole hemisphere, or the capture's direction samples. For each material a
// simulated capture (5 mirror positions, 15°…55° arms), one reconstruction (the ladder without
// validation folds, to keep the study short), the glTF version fitted both ways, and the sphere
// test (evaluate/sphere_test.h) of the rung and of each glTF version against the truth.
//
//   bench_gltf_source_study [WORK_DIR]   (prints a markdown table)
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "brdf/gltf_model.h"
#include "common/yaml_reader.h"
#include "evaluate/sphere_test.h"
#include "reconstruct/gltf_fit.h"
#include "reconstruct/pipeline.h"
#include "sim/sample_brdf.h"
#include "tests/reconstruct/capture_fixture.h"

namespace brdfrig {
namespace {

struct Row {
  std::string name, yaml;
};

int Main(int argc, char** argv) {
  namespace fs = std::filesystem;
  const fs::path work = argc > 1 ? fs::path(argv[1]) : fs::temp_directory_path() / "gltf_source";
  const std::string plastic = "diffuse: [0.3, 0.12, 0.05], f0: 0.04";
  const std::vector<Row> rows = {
      {"GGX alpha 0.1 (metal)", "{model: ggx, alpha: 0.1, diffuse: 0.0, f0: [0.9, 0.6, 0.3]}"},
      {"GGX alpha 0.3 (plastic)", "{model: ggx, alpha: 0.3, " + plastic + "}"},
      {"Cook-Torrance m 0.3", "{model: cook_torrance, alpha: 0.3, " + plastic + "}"},
      {"Ward alpha 0.1", "{model: ward, alpha: 0.1, specular: 0.3, diffuse: [0.15, 0.2, 0.3]}"},
      {"gray-plastic", "{model: nbrdf, name: gray-plastic}"},
      {"gold-metallic-paint", "{model: nbrdf, name: gold-metallic-paint}"},
      {"brass", "{model: nbrdf, name: brass}"},
      {"pink-fabric", "{model: nbrdf, name: pink-fabric}"},
  };
  std::printf(
      "| material | rung | rung vs truth (dB) | glTF from rung (dB) | glTF from samples (dB) "
      "| glTF vs rung (dB) | fit to rung (s) |\n|---|---|---|---|---|---|---|\n");
  for (const Row& row : rows) {
    const fs::path dir = work / std::to_string(&row - rows.data());
    reconstruct::testing::SceneSpec spec;
    spec.brdf = row.yaml;
    spec.width = 400;
    spec.height = 300;
    spec.supersampling = 2;
    spec.positions =
        "[{camera_arm: 15, light_arm: -15}, {camera_arm: 25, light_arm: -25}, "
        "{camera_arm: 35, light_arm: -35}, {camera_arm: 45, light_arm: -45}, "
        "{camera_arm: 55, light_arm: -55}]";
    try {
      const reconstruct::CaptureSet capture = reconstruct::testing::SimulateCapture(dir, spec);
      const auto truth = sim::ParseSampleBrdf(LoadYamlString(row.yaml, "study"), dir);
      reconstruct::ReconstructOptions options;
      options.validate = false;
      const reconstruct::ReconstructionResult from_rung =
          reconstruct::Reconstruct(capture, options);
      options.model = brdf::ModelKindName(from_rung.material.kind);
      options.gltf.source = "samples";
      const reconstruct::ReconstructionResult from_samples =
          reconstruct::Reconstruct(capture, options);
      const auto rung = evaluate::SphereTest(*truth, *from_rung.material.Model());
      const auto gltf_rung =
          evaluate::SphereTest(*truth, brdf::GltfModel(*from_rung.material.gltf));
      const auto gltf_samples =
          evaluate::SphereTest(*truth, brdf::GltfModel(*from_samples.material.gltf));
      std::printf("| %s | %s | %.2f | %.2f | %.2f | %s | %.2f |\n", row.name.c_str(),
                  brdf::ModelKindName(from_rung.material.kind), rung.mean_psnr_db,
                  gltf_rung.mean_psnr_db, gltf_samples.mean_psnr_db,
                  from_rung.material.gltf_fit["sphere_vs_model"]["mean_psnr_db"].dump().c_str(),
                  from_rung.stage_seconds.at("gltf"));
    } catch (const std::exception& e) {
      std::printf("| %s | failed: %s |\n", row.name.c_str(), e.what());
    }
    std::fflush(stdout);
  }
  return 0;
}

}  // namespace
}  // namespace brdfrig

int main(int argc, char** argv) { return brdfrig::Main(argc, argv); }
