// One point of the accuracy-versus-time studies (the seed's photo-count analysis and the sweep
// over the knobs that trade accuracy for time): simulate a capture of a scene with some
// settings, reconstruct, evaluate held-out views, and report accuracy and what it cost.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "brdf/material_file.h"
#include "evaluate/held_out.h"
#include "evaluate/material_report.h"
#include "geometry/rig_calibration.h"
#include "geometry/rig_geometry.h"
#include "prior/measured_prior.h"
#include "sim/scene.h"

namespace brdfrig::jobs {

struct StudySettings {
  std::filesystem::path scene;           // base scene (default: sim/scenes/default.yaml)
  std::vector<double> position_degrees;  // symmetric arms: camera_arm = θ, light_arm = −θ
  // An explicit plan (axis values in radians); when given it replaces position_degrees, so a
  // designed plan plugs in as its list of positions.
  std::vector<geometry::AxisPositions> positions;
  std::vector<double> exposures;  // empty: the scene's
  int width = 0, height = 0;      // 0: the scene's resolution
  int supersampling = 0;          // 0: the scene's render.supersampling
  // Changes to the loaded base scene (YAML flow text; empty: keep the scene's):
  std::string model;            // ladder rung to force (empty: chosen by validation)
  std::string sample_brdf;      // e.g. "{model: ward, alpha: 0.15, specular: 0.3, diffuse: 0.1}"
  std::string sensor_format;    // png16 | jpeg8 | tiff16
  std::string effects;          // e.g. "[{type: shot_noise, full_well: 30000}]"
  double bin_width_deg = 0.02;  // sample binning (0 = every pixel)
  int fit_iterations = 200;
  bool linear_interpolation = false;  // render with the seed's linear interpolation
  double view_elevation_deg = 40;
  std::vector<double> view_phis_deg = {0, 30, 60, 90, 120, 150, 180};
  // A rig that departs from the scene file's (a distorting lens, a darker paper, a light off its
  // nominal place): applied to the loaded scene, so the photos show the departed rig.
  std::function<void(sim::Scene*)> depart;
  // What the reconstruction believes about the rig instead of the scene's own (at the study's
  // resolution), and the calibrations applied to that belief (their flat field divides the
  // merged photos), as a lab's rig.yaml would give them.
  std::optional<geometry::RigGeometry> believed_rig;
  geometry::RigCalibrationFiles calibration;
  // Scratch space: the study makes a fresh directory inside it (creating work_dir when missing)
  // and removes only what it made.
  std::filesystem::path work_dir;
  // When set, the fit is judged with every figure (held-out views at every elevation, sphere
  // test, BRDF figures) into StudyResult::figures instead of the single-elevation views above.
  std::optional<evaluate::JudgeOptions> judge;
  // With `judge`: judge every fitted rung of the ladder with the same figures (one capture, one
  // reconstruction; the held-out truth photographed once per view) into StudyResult::rungs.
  bool judge_every_rung = false;
  // With `judge`: the CPU figures only (sphere test, BRDF figures), no held-out views.
  bool judge_brdf_only = false;
  // The measured prior of the `prior` rung (nullptr: the shipped one); a study of a measured
  // material passes one built without it.
  const prior::MeasuredPrior* prior = nullptr;
  // When set, the reconstructed material.json (with its glTF version) is also written here, so
  // a study's fits can be exported and drawn by other tools (bench_gltf_consumers).
  std::filesystem::path keep_material;
};

// One rung of the ladder judged (StudySettings::judge_every_rung).
struct RungFigures {
  std::string kind;  // brdf::ModelKindName
  bool fitted = false;
  std::string error;            // why the rung was not fitted
  bool chosen = false;          // the rung validation chose (the written material)
  double validation_score = 0;  // mean held-out score of the ladder (lower is better)
  double fit_seconds = 0;       // the rung's final fit (folds not included)
  std::size_t size_bytes = 0;   // the model in material.json
  evaluate::MaterialFigures figures;
  double brdf_error = 0;  // brdf::LogCosineError
};

struct StudyResult {
  std::vector<evaluate::HeldOutResult> views;
  evaluate::MaterialFigures
      figures;  // with StudySettings::judge (its held_out are also in `views`)
  double mean_psnr_whole = 0, mean_psnr_sample = 0;  // dB, averaged over views
  double brdf_error = 0;          // brdf::LogCosineError against the scene's sample
  double capture_time_s = 0;      // the rig's virtual clock: moves + exposures + downloads
  double reconstruct_time_s = 0;  // wall time of the reconstruction
  int slices = 0;
  int positions_used = 0;          // positions measured (target found, photos usable)
  brdf::Material material;         // the fit: its kind and every rung's validation scores (ladder)
  std::vector<RungFigures> rungs;  // with judge_every_rung: every rung of the ladder
  // With `judge`: the written material's glTF version (material.gltf, reconstruct/gltf_fit.h)
  // on the sphere test against the truth, as the fit is judged; empty when none was written.
  std::optional<evaluate::SphereTestResult> gltf_sphere;
  std::vector<std::string> warnings;
};

// The base scene, loaded, with the study's changes: resolution (same field of view: the focal
// length in pixels and the principal point follow the image size), the sample's BRDF, the
// sensor format and the effects list. Files the changes name resolve against the base scene's
// folder, as the scene's own do.
sim::Scene StudyScene(const std::filesystem::path& base, const StudySettings& settings);

StudyResult RunStudyPoint(const StudySettings& settings);

}  // namespace brdfrig::jobs
