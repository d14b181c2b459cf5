#include "evaluate/study.h"

#include <chrono>
#include <cmath>
#include <fstream>
#include <regex>

#include "brdf/metrics.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "reconstruct/batch.h"
#include "sim/scene.h"
#include "sim/simulate.h"

namespace brdfrig::evaluate {
namespace {

namespace fs = std::filesystem;
constexpr double kDeg = M_PI / 180;

// The base scene with another resolution (same field of view: the focal length is in mm).
std::string SceneWithResolution(const std::string& text, int width, int height) {
  if (width == 0) return text;
  return std::regex_replace(
      text, std::regex("resolution: \\[[0-9]+, *[0-9]+\\]"),
      "resolution: [" + std::to_string(width) + ", " + std::to_string(height) + "]");
}

}  // namespace

StudyResult RunStudyPoint(const StudySettings& s) {
  const fs::path base =
      s.scene.empty() ? fs::path(BRDFRIG_SOURCE_DIR) / "sim/scenes/default.yaml" : s.scene;
  if (s.work_dir.empty()) throw OptionsError("study: no work directory");
  fs::remove_all(s.work_dir);
  fs::create_directories(s.work_dir);
  const std::string text = ReadFileToString(base);
  if (std::regex_search(text, std::regex("file: *[^/ ]"))) {
    throw FileError(base.string(), "the study copies the scene: name its files by absolute path");
  }
  const fs::path scene_file = s.work_dir / "scene.yaml";
  WriteFileAtomically(scene_file, SceneWithResolution(text, s.width, s.height));
  StudyResult result;
  try {
    sim::SimulateOptions simulate;
    simulate.scene = scene_file;
    simulate.output_dir = s.work_dir / "capture";
    simulate.write_truth = false;
    simulate.exposures = s.exposures;
    for (double theta : s.position_degrees) {
      simulate.positions.push_back({{"camera_arm", theta * kDeg}, {"light_arm", -theta * kDeg}});
    }
    result.capture_time_s = sim::Simulate(simulate).virtual_time_s;
    const sim::Scene scene = sim::LoadScene(scene_file);

    const auto start = std::chrono::steady_clock::now();
    reconstruct::ReconstructOptions options;
    options.samples.bin_width = s.bin_width_deg * kDeg;
    options.fit.max_iterations = s.fit_iterations;
    const reconstruct::ReconstructionResult fit =
        reconstruct::Reconstruct(reconstruct::LoadCapture(s.work_dir / "capture"), options);
    result.reconstruct_time_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    result.slices = static_cast<int>(fit.material.slices.size());
    result.warnings = fit.warnings;
    const brdf::SliceModel model = fit.material.Model();
    result.brdf_error = brdf::LogCosineError(*scene.sample.brdf, model);

    std::vector<double> phis;
    for (double d : s.view_phis_deg) phis.push_back(d * kDeg);
    HeldOutOptions held_out;
    held_out.linear_interpolation = s.linear_interpolation;
    result.views = EvaluateHeldOut(scene, model,
                                   OrientationViews(s.view_elevation_deg * kDeg, phis), held_out);
    for (const HeldOutResult& v : result.views) {
      result.mean_psnr_whole += v.whole_photo.psnr_db / static_cast<double>(result.views.size());
      result.mean_psnr_sample += v.sample_only.psnr_db / static_cast<double>(result.views.size());
    }
  } catch (...) {
    fs::remove_all(s.work_dir);
    throw;
  }
  fs::remove_all(s.work_dir);
  return result;
}

}  // namespace brdfrig::evaluate
