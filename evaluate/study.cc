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

// The base scene with the study's replacements: resolution (same field of view: the focal
// length is in mm), the sample's BRDF, the sensor format and the effects list.
std::string StudyScene(std::string text, const StudySettings& s) {
  const auto replace = [&](const std::string& pattern, const std::string& with) {
    const std::regex re(pattern);
    if (!std::regex_search(text, re)) {
      throw OptionsError("study: the base scene has no line matching '" + pattern + "'");
    }
    text = std::regex_replace(text, re, with, std::regex_constants::format_first_only);
  };
  if (s.width != 0) {
    replace("resolution: \\[[0-9]+, *[0-9]+\\]",
            "resolution: [" + std::to_string(s.width) + ", " + std::to_string(s.height) + "]");
  }
  if (s.supersampling != 0) {
    replace("supersampling: [0-9]+", "supersampling: " + std::to_string(s.supersampling));
  }
  if (!s.sample_brdf.empty()) replace("brdf: \\{[^\n]*\\}", "brdf: " + s.sample_brdf);
  if (!s.sensor_format.empty()) replace("format: [a-z0-9]+", "format: " + s.sensor_format);
  if (!s.effects.empty()) {
    // The effects list is the scene's last section.
    const auto at = text.find("\neffects:");
    if (at == std::string::npos) throw OptionsError("study: the base scene has no effects list");
    text = text.substr(0, at) + "\neffects: " + s.effects + "\n";
  }
  return text;
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
  WriteFileAtomically(scene_file, StudyScene(text, s));
  StudyResult result;
  try {
    sim::SimulateOptions simulate;
    simulate.scene = scene_file;
    simulate.output_dir = s.work_dir / "capture";
    simulate.write_truth = false;
    simulate.exposures = s.exposures;
    simulate.positions = s.positions;
    if (s.positions.empty()) {
      for (double theta : s.position_degrees) {
        simulate.positions.push_back({{"camera_arm", theta * kDeg}, {"light_arm", -theta * kDeg}});
      }
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
    if (s.judge) {
      JudgeOptions judge = *s.judge;
      judge.held_out.linear_interpolation = s.linear_interpolation;
      result.figures = JudgeFit(scene, model, judge);
      result.brdf_error = result.figures.brdf.log_cosine_error;
      result.views = result.figures.held_out;
      for (const HeldOutResult& v : result.views) {
        result.mean_psnr_whole += v.whole_photo.psnr_db / static_cast<double>(result.views.size());
        result.mean_psnr_sample += v.sample_only.psnr_db / static_cast<double>(result.views.size());
      }
      fs::remove_all(s.work_dir);
      return result;
    }
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
