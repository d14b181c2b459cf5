#include "jobs/study.h"

#include <stdlib.h>

#include <chrono>
#include <cmath>
#include <memory>

#include "brdf/gltf_model.h"
#include "brdf/metrics.h"
#include "common/angles.h"
#include "common/error.h"
#include "common/yaml_reader.h"
#include "reconstruct/batch.h"
#include "sim/effects.h"
#include "sim/sample_brdf.h"
#include "sim/scene.h"
#include "sim/simulate.h"

namespace brdfrig::jobs {
namespace {

namespace fs = std::filesystem;

// A scratch directory the study makes for itself inside work_dir (created when missing), and
// removes again with everything in it. work_dir itself is removed only when this made it and
// it is empty: the study never removes a directory it did not create.
class ScratchDir {
 public:
  explicit ScratchDir(const fs::path& parent) : parent_(parent) {
    created_parent_ = fs::create_directories(parent);
    std::string name = (parent / "study-XXXXXX").string();
    if (mkdtemp(name.data()) == nullptr) {
      throw Error("study: cannot create a scratch directory in " + parent.string());
    }
    path_ = name;
  }
  ~ScratchDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
    if (created_parent_) fs::remove(parent_, ec);  // only when empty
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path parent_, path_;
  bool created_parent_ = false;
};

// The study's mean whole-photo and sample-only PSNR over its held-out views.
void AverageViews(StudyResult* result) {
  const double n = static_cast<double>(result->views.size());
  for (const evaluate::HeldOutResult& v : result->views) {
    result->mean_psnr_whole += v.whole_photo.psnr_db / n;
    result->mean_psnr_sample += v.sample_only.psnr_db / n;
  }
}

// What exporting costs against the truth: the glTF version reconstruct wrote beside the
// chosen rung, on the same sphere test as the rung (docs/gltf.md).
void JudgeGltfVersion(const brdf::Brdf& truth, const brdf::Material& material,
                      const evaluate::SphereTestOptions& sphere, StudyResult* result) {
  if (!material.gltf) return;
  result->gltf_sphere = evaluate::SphereTest(truth, brdf::GltfModel(*material.gltf), sphere);
}

}  // namespace

sim::Scene StudyScene(const fs::path& base, const StudySettings& s) {
  sim::Scene scene = sim::LoadScene(base);
  if (s.width != 0) {
    geometry::Intrinsics& k = scene.rig.intrinsics;
    const double sx = static_cast<double>(s.width) / k.width;
    const double sy = static_cast<double>(s.height) / k.height;
    k.fx *= sx;
    k.fy *= sx;
    k.cx *= sx;
    k.cy *= sy;
    k.width = s.width;
    k.height = s.height;
  }
  if (s.supersampling != 0) scene.render.supersampling = s.supersampling;
  if (!s.sample_brdf.empty()) {
    const YamlNode root = LoadYamlString("brdf: " + s.sample_brdf, "StudySettings.sample_brdf");
    scene.sample.brdf = sim::ParseSampleBrdf(root.Required("brdf"), base.parent_path());
  }
  if (!s.sensor_format.empty()) {
    const auto format = sim::PhotoFormatNamed(s.sensor_format);
    if (!format) {
      throw OptionsError("StudySettings.sensor_format = " + s.sensor_format +
                         "; must be png16, tiff16 or jpeg8");
    }
    scene.sensor.format = *format;
  }
  if (!s.effects.empty()) {
    const YamlNode root = LoadYamlString("effects: " + s.effects, "StudySettings.effects");
    scene.effects = sim::ParseEffects(root.Required("effects"));
  }
  if (s.depart) s.depart(&scene);
  return scene;
}

StudyResult RunStudyPoint(const StudySettings& s) {
  const fs::path base =
      s.scene.empty() ? fs::path(BRDFRIG_SOURCE_DIR) / "sim/scenes/default.yaml" : s.scene;
  if (s.work_dir.empty())
    throw OptionsError("StudySettings.work_dir is empty; must name a directory");
  const auto scene = std::make_shared<const sim::Scene>(StudyScene(base, s));
  const ScratchDir scratch(s.work_dir);
  StudyResult result;
  sim::SimulateOptions simulate;
  simulate.scene = base;
  simulate.loaded_scene = scene;
  simulate.output_dir = scratch.path() / "capture";
  simulate.write_truth = false;
  simulate.exposures = s.exposures;
  simulate.positions = s.positions;
  if (s.positions.empty()) {
    for (double theta : s.position_degrees) {
      simulate.positions.push_back(
          {{"camera_arm", Radians(theta)}, {"light_arm", -Radians(theta)}});
    }
  }
  result.capture_time_s = sim::Simulate(simulate).virtual_time_s;

  const auto start = std::chrono::steady_clock::now();
  reconstruct::ReconstructOptions options;
  options.samples.bin_width = Radians(s.bin_width_deg);
  options.fit.max_iterations = s.fit_iterations;
  options.model = s.model;
  options.prior.prior = s.prior;
  // capture.json names the base scene; the nominal geometry is the edited scene's.
  reconstruct::CaptureSet capture = reconstruct::LoadCapture(scratch.path() / "capture");
  capture.nominal = s.believed_rig.value_or(scene->rig);
  if (!s.calibration.Empty()) {
    geometry::ApplyRigCalibration(s.calibration, "", &capture.nominal);
    capture.calibration = s.calibration;
  }
  const reconstruct::ReconstructionResult fit = reconstruct::Reconstruct(capture, options);
  result.reconstruct_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!s.keep_material.empty()) brdf::WriteMaterialFile(s.keep_material, fit.material);
  result.slices = static_cast<int>(fit.material.slices.size());
  result.warnings = fit.warnings;
  result.material = fit.material;
  result.positions_used = 0;
  for (const reconstruct::PositionReport& p : fit.positions) result.positions_used += p.used;
  const std::shared_ptr<const brdf::Brdf> fitted_model = fit.material.Model();
  const brdf::Brdf& model = *fitted_model;
  if (s.judge && s.judge_every_rung) {
    evaluate::JudgeOptions judge = *s.judge;
    judge.held_out.linear_interpolation = s.linear_interpolation;
    std::vector<std::shared_ptr<const brdf::Brdf>> models;
    std::vector<const brdf::Brdf*> judged;
    std::vector<std::size_t> judged_rung;
    for (const reconstruct::RungResult& r : fit.ladder.rungs) {
      RungFigures rung;
      rung.kind = brdf::ModelKindName(r.kind);
      rung.fitted = r.fitted;
      rung.error = r.error;
      rung.chosen = r.chosen;
      rung.validation_score = r.score;
      rung.fit_seconds = r.fit_seconds;
      rung.size_bytes = r.size_bytes;
      if (r.fitted) {
        models.push_back(r.material.Model());
        judged.push_back(models.back().get());
        judged_rung.push_back(result.rungs.size());
      }
      result.rungs.push_back(std::move(rung));
    }
    std::vector<evaluate::MaterialFigures> figures;
    if (s.judge_brdf_only) {
      for (const brdf::Brdf* m : judged) {
        figures.push_back(evaluate::JudgeBrdf(*scene->sample.brdf, *m, judge.sphere, judge.brdf));
      }
    } else {
      figures = evaluate::JudgeFitEach(*scene, judged, judge);
    }
    for (std::size_t i = 0; i < judged.size(); ++i) {
      RungFigures& rung = result.rungs[judged_rung[i]];
      rung.figures = std::move(figures[i]);
      rung.brdf_error = rung.figures.brdf.log_cosine_error;
      if (rung.chosen) result.figures = rung.figures;
    }
    result.brdf_error = result.figures.brdf.log_cosine_error;
    result.views = result.figures.held_out;
    AverageViews(&result);
    JudgeGltfVersion(*scene->sample.brdf, fit.material, judge.sphere, &result);
    return result;
  }
  if (s.judge) {
    evaluate::JudgeOptions judge = *s.judge;
    judge.held_out.linear_interpolation = s.linear_interpolation;
    result.figures = s.judge_brdf_only
                         ? evaluate::JudgeBrdf(*scene->sample.brdf, model, judge.sphere, judge.brdf)
                         : evaluate::JudgeFit(*scene, model, judge);
    result.brdf_error = result.figures.brdf.log_cosine_error;
    result.views = result.figures.held_out;
    AverageViews(&result);
    JudgeGltfVersion(*scene->sample.brdf, fit.material, judge.sphere, &result);
    return result;
  }
  result.brdf_error = brdf::LogCosineError(*scene->sample.brdf, model);

  std::vector<double> phis;
  for (double d : s.view_phis_deg) phis.push_back(Radians(d));
  evaluate::HeldOutOptions held_out;
  held_out.linear_interpolation = s.linear_interpolation;
  result.views = evaluate::EvaluateHeldOut(
      *scene, model, evaluate::OrientationViews(Radians(s.view_elevation_deg), phis), held_out);
  AverageViews(&result);
  return result;
}

}  // namespace brdfrig::jobs
