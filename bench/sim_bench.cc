// Prints a table: time per camera image (radiance + sensor pipeline) of the default scene
// (1600×1200, GGX sample) for the ideal camera, each effect alone, and all effects listed but
// disabled, with the ratio to the ideal camera measured in the same run (best of --reps).
//   bench_sim [--reps N] [--threads N]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "common/atomic_file.h"
#include "common/parallel.h"
#include "sim/simulator.h"

namespace {

using brdfrig::sim::Scene;
using brdfrig::sim::Simulator;

double SecondsPerImage(const Scene& scene, int reps, int threads) {
  const Simulator simulator(scene);
  const brdfrig::geometry::AxisPositions& positions = scene.capture.positions.at(2);  // 35°
  brdfrig::sim::RenderOptions options;
  options.threads = threads;
  double best = 1e300;
  for (int r = 0; r < reps; ++r) {
    const auto start = std::chrono::steady_clock::now();
    const cv::Mat image = simulator.RenderCameraImage(positions, 0.0166667, 1, options);
    best = std::min(
        best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    if (image.empty()) std::abort();
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  int reps = 3, threads = 0;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--reps")) reps = std::atoi(argv[i + 1]);
    if (!std::strcmp(argv[i], "--threads")) threads = std::atoi(argv[i + 1]);
  }
  const std::string path = std::string(BRDFRIG_SOURCE_DIR) + "/sim/scenes/default.yaml";
  std::string text = brdfrig::ReadFileToString(path);
  text = text.substr(0, text.find("\neffects:")) + "\n";
  auto scene_with = [&](const std::string& effects) {
    return brdfrig::sim::LoadSceneString(text + effects, "default.yaml",
                                         BRDFRIG_SOURCE_DIR "/sim/scenes");
  };
  const std::vector<std::string> effects = {
      "type: area_light, radius: 0.01, samples: 16",
      "type: ambient, radiance: 0.05",
      "type: radial_distortion, k1: -0.05, k2: 0.01",
      "type: vignetting, falloff: cos4",
      "type: shot_noise, full_well: 30000",
      "type: read_noise, sigma: 0.0005",
      "type: saturation, level: 1.0",
      "type: quantization, bits: 14",
      "type: response_curve, curve: srgb",
      "type: mechanical_error, backlash_deg: 0.05, jitter_deg: 0.01"};
  std::string all_disabled = "effects:\n";
  std::string all_enabled = "effects:\n";
  for (const std::string& e : effects) {
    all_disabled += "  - {" + e + ", enabled: false}\n";
    all_enabled += "  - {" + e + "}\n";
  }

  const Scene ideal = scene_with("");
  const double megapixels = ideal.rig.intrinsics.width * ideal.rig.intrinsics.height / 1e6;
  std::printf("default scene %dx%d, %s; threads: %d; best of %d\n", ideal.rig.intrinsics.width,
              ideal.rig.intrinsics.height, ideal.sample.brdf->Name().c_str(),
              threads > 0 ? threads : brdfrig::DefaultThreadCount(), reps);
  std::printf("%-48s %10s %8s %10s\n", "configuration", "ms/image", "MP/s", "vs ideal");
  const double t_ideal = SecondsPerImage(ideal, reps, threads);
  auto row = [&](const std::string& name, double t) {
    std::printf("%-48s %10.1f %8.2f %9.2fx\n", name.c_str(), 1e3 * t, megapixels / t, t / t_ideal);
  };
  row("ideal camera (supersampling 4 at edges)", t_ideal);
  Scene no_ss = ideal;
  no_ss.render.supersampling = 1;
  row("ideal camera, no supersampling", SecondsPerImage(no_ss, reps, threads));
  if (threads != 1) {
    const double t1 = SecondsPerImage(ideal, reps, 1);
    row("ideal camera, 1 thread", t1);
  }
  for (const std::string& e : effects) {
    const std::string name = e.substr(6, e.find(',') - 6);
    row("+ " + name, SecondsPerImage(scene_with("effects:\n  - {" + e + "}\n"), reps, threads));
  }
  row("all effects enabled", SecondsPerImage(scene_with(all_enabled), reps, threads));
  // Interleaved, so that drift of the machine affects both alike.
  double best_ideal = 1e300, best_disabled = 1e300;
  const Scene disabled = scene_with(all_disabled);
  for (int r = 0; r < 2 * reps; ++r) {
    best_ideal = std::min(best_ideal, SecondsPerImage(ideal, 1, threads));
    best_disabled = std::min(best_disabled, SecondsPerImage(disabled, 1, threads));
  }
  std::printf(
      "\nlisted-but-disabled vs ideal (interleaved, best of %d): %.1f ms vs %.1f ms = %.3fx\n",
      2 * reps, 1e3 * best_disabled, 1e3 * best_ideal, best_disabled / best_ideal);
  return 0;
}
