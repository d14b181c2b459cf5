// The reconstruction of one capture, in three stages: measure each position (HDR merge →
// target and pose → light → radiometry → samples; reconstruct/measure_position.h), then fit
// every rung of the model ladder and choose one by validation (reconstruct/fit_ladder.h).
// Positions whose photos are missing, corrupt, changed since capture (SHA-256 recorded in the
// session), grey, or whose target cannot be found, are dropped with the reason in the report
// and in material.json's provenance; no usable position is an error, and so is any dropped
// position under `strict`.
#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "brdf/material_file.h"
#include "reconstruct/capture_set.h"
#include "reconstruct/fit_ladder.h"
#include "reconstruct/gltf_fit.h"
#include "reconstruct/measure_position.h"

namespace brdfrig::reconstruct {

struct ReconstructOptions {
  HdrMergeOptions hdr;
  TargetOptions target;
  LightOptions light;
  LightRefineOptions light_refine;
  RadiometryOptions radiometry;
  SampleOptions samples;
  SliceFitOptions fit;
  DirectionSampleOptions directions;
  MicrofacetFitOptions microfacet;
  PriorRungOptions prior;  // the measured prior the `prior` rung uses (default: the shipped one)
  GltfFitOptions gltf;     // the chosen rung's glTF version, written beside it (gltf_fit.h)
  // The model kind written: empty = every rung of the ladder fitted and the best by validation
  // chosen; a kind name ("seed", "seed_constrained", "microfacet", "ggx", "beckmann") = only
  // that rung.
  std::string model;
  bool validate = true;            // leave-one-position-out folds when choosing
  std::filesystem::path hdr_dir;   // when set: pNN.exr (radiance) and pNN_valid.png written there
  std::vector<int> use_positions;  // position indices to use; empty = all
  // Position indices measured but never fitted: every rung is scored on them (a plan's
  // validation photos).
  std::vector<int> validation_positions;
  // Any dropped or degraded position is an error (Reconstruct throws; nothing is written): for
  // batch scripts that must not accept a material from fewer positions than were captured.
  bool strict = false;
  void Validate() const;
  // Every option that changes the material (not hdr_dir, threads or strict), as JSON: recorded
  // in the material's provenance ("options"), part of batch reprocessing's up-to-date key.
  nlohmann::json ResultKey() const;
};

struct ReconstructionResult {
  brdf::Material material;
  std::vector<PositionReport> positions;
  LadderResult ladder;  // every rung fitted, with its scores; material is the chosen one
  std::vector<std::string> warnings;
  // Wall and CPU time per stage: "measure" (every position, wall and process CPU) and within
  // it load, hdr, target, light, radiometry, samples (summed over positions, which are measured
  // on several threads at once; CPU of the measuring thread), then "fit" and "gltf" (process).
  std::map<std::string, double> stage_seconds, stage_cpu_seconds;
  // The capture's validation positions (photos, exposures, axis readings), left out of the fit:
  // what a report compares with the fit's rendering.
  std::vector<CapturePosition> validation;
  std::string Summary() const;  // a short human report
  // "p03: <reason>" for every position dropped (loader or measurement); empty = complete.
  std::vector<std::string> Dropped() const;
  // "p03: <reason>" for every position used although its photos are damaged (NaN or infinite
  // pixels, masked as invalid): the material is written but marked partial, like a dropped
  // position (exit status 3, refused under --strict). Empty = every used photo was clean.
  std::vector<std::string> Degraded() const;
};

using ProgressCallback = std::function<void(const std::string&)>;

ReconstructionResult Reconstruct(const CaptureSet& capture, const ReconstructOptions& options,
                                 const ProgressCallback& progress = {});

}  // namespace brdfrig::reconstruct
