// Stage 1 of the reconstruction: one capture position's photos → HDR radiance → cut-out corners
// and camera pose → light → paper radiometry → BRDF samples, both binned by theta for the
// seed's slices and with their directions for the microfacet fits. A position that cannot be
// measured throws brdfrig::Error with the reason (the pipeline reports it and goes on).
#pragma once

#include <filesystem>
#include <map>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "reconstruct/capture_set.h"
#include "reconstruct/direction_samples.h"
#include "reconstruct/hdr_merge.h"
#include "reconstruct/light_estimate.h"
#include "reconstruct/light_refine.h"
#include "reconstruct/marker_pose.h"
#include "reconstruct/radiometry.h"
#include "reconstruct/samples.h"
#include "reconstruct/slice_fit.h"
#include "reconstruct/target.h"

namespace brdfrig::reconstruct {

struct PositionReport {
  int index = 0;
  bool used = false;
  std::string skipped_reason;  // why the position was left out (used == false)
  double theta_in = 0;
  double invalid_fraction = 0;  // pixels clipped in every exposure
  long non_finite_pixels = 0;   // NaN/Inf in any exposure (float photos): marked invalid
  double reprojection_rms_px = 0;
  // What the pose came from: "markers" (the marker mask's corners) or "cut-out" (its four).
  std::string pose_from = "cut-out";
  int pose_points = 0;               // corners the pose was fitted to
  double camera_disagreement_m = 0;  // measured vs nominal camera centre
  double edge_line_rms_px = 0;       // scatter of the cut-out edge points about their lines
  LightEstimate light;               // position: after refinement
  double light_refinement_rad = 0;   // how far the joint fit moved the highlight's light
  Radiometry radiometry;
  int samples = 0;
  int direction_samples = 0;  // after block averaging
  // Sample-region pixels darker than the sensor's noise floor in the longest exposure
  // (HdrImage::noise_floor): left out of the direction samples, so not measured.
  double below_noise_floor_fraction = 0;
  std::vector<std::string> warnings;
};

struct MeasureOptions {
  HdrMergeOptions hdr;
  TargetOptions target;
  LightOptions light;
  LightRefineOptions light_refine;
  RadiometryOptions radiometry;
  SampleOptions samples;
  DirectionSampleOptions directions;
  SliceFitOptions fit;            // the slice fit the light refinement uses
  std::filesystem::path hdr_dir;  // when set: pNN.exr and pNN_valid.png written there
};

// Everything measured at one position before any model is fitted.
struct MeasuredPosition {
  PositionReport report;
  BrdfSamples samples;          // binned by theta (the seed's slices)
  DirectionSamples directions;  // with directions (the microfacet rungs)
  geometry::CameraPose pose;    // measured from the markers or the cut-out (camera_from_world)
};

// State shared by the positions of one capture.
struct MeasureState {
  cv::Mat gain;         // the rig's flat field (gain_map.h); empty: none
  cv::Mat response;     // recovered once per capture for non-linear (8-bit) photos
  HdrImage hdr;         // one buffer reused by every position's merge: the last position's HDR
  bool merged = false;  // a bracket was merged (with 8-bit photos: `response` is recovered)
  std::map<std::string, double>* stage_seconds = nullptr;  // wall, per stage
  // CPU of the measuring thread per stage (positions may be measured on several threads at
  // once; the HDR merge's helper threads are not counted).
  std::map<std::string, double>* stage_cpu_seconds = nullptr;
};

std::string PositionName(int index);  // "p03"

MeasuredPosition MeasurePosition(const CapturePosition& position,
                                 const geometry::RigGeometry& nominal,
                                 const MeasureOptions& options, MeasureState* state);

}  // namespace brdfrig::reconstruct
