// The reconstruction of one capture: per position HDR merge → target and pose → light →
// radiometry → BRDF samples, then one slice fit per position, sharing what single slices
// cannot determine. Positions whose photos are missing or corrupt, or whose target cannot be
// found, are skipped with the reason in the report; no usable position is an error.
#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "brdf/material_file.h"
#include "reconstruct/capture_set.h"
#include "reconstruct/hdr_merge.h"
#include "reconstruct/light_estimate.h"
#include "reconstruct/light_refine.h"
#include "reconstruct/radiometry.h"
#include "reconstruct/samples.h"
#include "reconstruct/slice_fit.h"
#include "reconstruct/target.h"

namespace brdfrig::reconstruct {

struct ReconstructOptions {
  HdrMergeOptions hdr;
  TargetOptions target;
  LightOptions light;
  LightRefineOptions light_refine;
  RadiometryOptions radiometry;
  SampleOptions samples;
  SliceFitOptions fit;
  std::filesystem::path hdr_dir;   // when set: pNN.exr (radiance) and pNN_valid.png written there
  std::vector<int> use_positions;  // position indices to use; empty = all
  void Validate() const;
};

struct PositionReport {
  int index = 0;
  bool used = false;
  std::string skipped_reason;  // why the position was left out (used == false)
  double theta_in = 0;
  double invalid_fraction = 0;  // pixels clipped in every exposure
  double reprojection_rms_px = 0;
  double camera_disagreement_m = 0;  // measured vs nominal camera centre
  double edge_line_rms_px = 0;       // scatter of the cut-out edge points about their lines
  LightEstimate light;               // position: after refinement
  double light_refinement_rad = 0;   // how far the joint fit moved the highlight's light
  Radiometry radiometry;
  int samples = 0;
  std::vector<std::string> warnings;
};

struct ReconstructionResult {
  brdf::Material material;
  std::vector<PositionReport> positions;
  std::vector<std::string> warnings;
  std::map<std::string, double> stage_seconds;  // wall time per stage, summed over positions
  // The capture's validation positions (photos, exposures, axis readings), left out of the fit:
  // what a report compares with the fit's rendering.
  std::vector<CapturePosition> validation;
  std::string Summary() const;  // a short human report
};

using ProgressCallback = std::function<void(const std::string&)>;

ReconstructionResult Reconstruct(const CaptureSet& capture, const ReconstructOptions& options,
                                 const ProgressCallback& progress = {});

}  // namespace brdfrig::reconstruct
