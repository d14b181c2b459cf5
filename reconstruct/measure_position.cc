#include "reconstruct/measure_position.h"
#include "common/angles.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <opencv2/imgcodecs.hpp>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/exr_io.h"
#include "common/format.h"
#include "reconstruct/gain_map.h"
#include "reconstruct/stage_timer.h"

namespace brdfrig::reconstruct {
namespace {

struct LoadedBracket {
  std::vector<cv::Mat> images;
  std::vector<double> exposures;
  cv::Mat non_finite;  // CV_8U, 255 where a float photo holds NaN/Inf in any channel
};

// NaN/Inf in a float photo (EXR, float TIFF) is corrupt data, not light: it must neither
// vanish silently from the merge nor pass for a highlight.
void MarkNonFinite(const cv::Mat& image, cv::Mat* mask) {
  if (image.depth() != CV_32F) return;
  if (mask->empty()) *mask = cv::Mat::zeros(image.size(), CV_8U);
  for (int y = 0; y < image.rows; ++y) {
    const float* row = image.ptr<float>(y);
    uchar* out = mask->ptr<uchar>(y);
    for (int x = 0; x < image.cols * image.channels(); ++x) {
      if (!std::isfinite(row[x])) out[x / image.channels()] = 255;
    }
  }
}

LoadedBracket LoadBracket(const CapturePosition& position, const geometry::Intrinsics& intrinsics) {
  if (position.frames.empty()) throw Error("no photos recorded");
  LoadedBracket bracket;
  for (const BracketFrame& frame : position.frames) {
    cv::Mat image = ReadPhoto(frame.file.string());
    if (image.cols != intrinsics.width || image.rows != intrinsics.height) {
      throw FileError(frame.file.string(), "photo is " + std::to_string(image.cols) + "×" +
                                               std::to_string(image.rows) + ", the rig's camera " +
                                               std::to_string(intrinsics.width) + "×" +
                                               std::to_string(intrinsics.height));
    }
    if (!bracket.images.empty() && image.type() != bracket.images[0].type()) {
      throw FileError(frame.file.string(), "photo format differs from the rest of its bracket");
    }
    MarkNonFinite(image, &bracket.non_finite);
    bracket.images.push_back(std::move(image));
    bracket.exposures.push_back(frame.exposure_s);
  }
  return bracket;
}

// The pose from the marker mask's corners when the rig has one and enough markers are found,
// else from the cut-out's corners (a marker pose that fails its checks falls back too, saying
// why).
PoseEstimate MeasurePose(const HdrImage& hdr, const geometry::RigGeometry& nominal,
                         const geometry::CameraPose& nominal_pose, const MeasureOptions& options,
                         PositionReport* report) {
  if (nominal.target.markers) {
    const MarkerCorners markers =
        FindMaskMarkers(hdr.radiance, hdr.valid, nominal.intrinsics, nominal.target);
    if (markers.markers >= options.target.min_markers) {
      try {
        const PoseEstimate pose =
            PoseFromPlanePoints(markers.world, markers.image, nominal.intrinsics, nominal_pose,
                                options.target, "the mask's marker corners");
        report->pose_from = "markers";
        report->pose_points = static_cast<int>(markers.image.size());
        return pose;
      } catch (const Error& e) {
        report->warnings.push_back(std::string("pose from the cut-out: ") + e.what());
      }
    } else {
      report->warnings.push_back(
          "pose from the cut-out: " + std::to_string(markers.markers) +
          " of the marker mask's markers found (at least " +
          std::to_string(options.target.min_markers) +
          " wanted; are they in view, sharp, and is the rig's target.markers the printed mask?)");
    }
  }
  const TargetCorners corners = FindCutoutCorners(hdr.radiance, hdr.valid, nominal.intrinsics,
                                                  nominal_pose, nominal.target, options.target);
  report->pose_from = "cut-out";
  report->pose_points = 4;
  report->edge_line_rms_px = corners.line_rms_px;
  return EstimatePose(corners, nominal.intrinsics, nominal.target, nominal_pose, options.target);
}

}  // namespace

std::string PositionName(int index) {
  char name[16];
  std::snprintf(name, sizeof(name), "p%02d", index);
  return name;
}

MeasuredPosition MeasurePosition(const CapturePosition& position,
                                 const geometry::RigGeometry& nominal,
                                 const MeasureOptions& options, MeasureState* state) {
  MeasuredPosition data;
  PositionReport& report = data.report;
  report.index = position.index;
  const std::string name = PositionName(position.index);
  HdrImage& hdr = state->hdr;
  LoadedBracket bracket;
  {
    StageTimer timer(state->stage_seconds, state->stage_cpu_seconds, "load", CpuClock::kThread);
    bracket = LoadBracket(position, nominal.intrinsics);
  }
  {
    StageTimer timer(state->stage_seconds, state->stage_cpu_seconds, "hdr", CpuClock::kThread);
    if (bracket.images[0].depth() == CV_8U && state->response.empty()) {
      state->response = RecoverResponse(bracket.images, bracket.exposures);
    }
    MergeBracketInto(bracket.images, bracket.exposures, state->response, &hdr, options.hdr);
    ApplyGainMap(state->gain, &hdr);
    state->merged = true;
  }
  if (!bracket.non_finite.empty()) {
    report.non_finite_pixels = cv::countNonZero(bracket.non_finite);
  }
  if (report.non_finite_pixels > 0) {
    hdr.valid.setTo(0, bracket.non_finite);
    hdr.radiance.setTo(cv::Scalar::all(0), bracket.non_finite);
    hdr.invalid_fraction = static_cast<double>(hdr.valid.total() - cv::countNonZero(hdr.valid)) /
                           static_cast<double>(hdr.valid.total());
    report.warnings.push_back(std::to_string(report.non_finite_pixels) +
                              " pixels are NaN or infinite in the photos: treated as invalid "
                              "(a corrupt or badly converted float image)");
  }
  report.invalid_fraction = hdr.invalid_fraction;
  if (!options.hdr_dir.empty()) {
    StageTimer timer(state->stage_seconds, state->stage_cpu_seconds, "write", CpuClock::kThread);
    WriteRadianceExr(options.hdr_dir / (name + ".exr"), hdr.radiance);
    std::vector<std::uint8_t> png;
    cv::imencode(".png", hdr.valid, png);
    WriteFileAtomically(options.hdr_dir / (name + "_valid.png"),
                        std::string(png.begin(), png.end()));
  }
  const geometry::CameraPose nominal_pose = nominal.CameraAt(position.axis_readings);
  PoseEstimate pose;
  {
    StageTimer timer(state->stage_seconds, state->stage_cpu_seconds, "target", CpuClock::kThread);
    pose = MeasurePose(hdr, nominal, nominal_pose, options, &report);
  }
  report.reprojection_rms_px = pose.reprojection_rms_px;
  report.camera_disagreement_m = pose.nominal_disagreement_m;
  if (pose.nominal_disagreement_m > options.target.warn_camera_offset_m) {
    report.warnings.push_back("camera pose " + Fixed(pose.nominal_disagreement_m * 1e3, 1) +
                              " mm from the rig's nominal: check the rig file, or the cut-out's "
                              "edges in badly exposed photos");
  }
  data.pose = pose.pose;
  const PlaneView view(nominal.intrinsics, pose.pose);
  {
    StageTimer timer(state->stage_seconds, state->stage_cpu_seconds, "light", CpuClock::kThread);
    report.light = EstimateLight(hdr.radiance, hdr.valid, view, nominal.target,
                                 nominal.LightAt(position.axis_readings), options.light);
  }
  for (const std::string& w : report.light.warnings) report.warnings.push_back(w);
  {
    StageTimer timer(state->stage_seconds, state->stage_cpu_seconds, "radiometry",
                     CpuClock::kThread);
    report.radiometry = CalibrateFromPaper(hdr.radiance, hdr.valid, view, report.light.position,
                                           nominal.target, options.radiometry);
  }
  if (report.radiometry.relative_spread > options.radiometry.warn_spread) {
    report.warnings.push_back(
        "paper brightness spread " + Fixed(report.radiometry.relative_spread, 2) +
        ": the paper is noisy, clipped or unevenly lit in every exposure, so the BRDF scale "
        "is unreliable (bracket so that the paper is well exposed in one exposure)");
  }
  {
    StageTimer timer(state->stage_seconds, state->stage_cpu_seconds, "samples", CpuClock::kThread);
    data.samples = ExtractSamples(hdr.radiance, hdr.valid, view, report.light.position,
                                  report.radiometry, nominal.target, options.samples);
  }
  if (data.samples.theta.size() < 16) {
    throw Error("only " + std::to_string(data.samples.pixels_used) + " usable sample pixels (" +
                std::to_string(data.samples.pixels_invalid) +
                " clipped in every exposure): add a shorter exposure");
  }
  if (report.light.from_highlight && options.light_refine.enabled) {
    StageTimer timer(state->stage_seconds, state->stage_cpu_seconds, "light", CpuClock::kThread);
    const LightRefinement refined = RefineLight(
        hdr.radiance, hdr.valid, view, nominal.target, options.samples, report.light.position,
        report.radiometry, FitSlice(data.samples, options.fit), options.light_refine);
    if (refined.accepted) {
      report.light_refinement_rad = refined.shift_rad;
      report.light.position = refined.position;
      const geometry::Vec3 nominal_light = nominal.LightAt(position.axis_readings);
      const geometry::Vec3 at = report.light.highlight_in_world;
      const geometry::Vec3 a = refined.position - at, b = nominal_light - at;
      report.light.nominal_disagreement_rad = std::atan2(a.cross(b).norm(), a.dot(b));
      report.radiometry = CalibrateFromPaper(hdr.radiance, hdr.valid, view, report.light.position,
                                             nominal.target, options.radiometry);
      data.samples = ExtractSamples(hdr.radiance, hdr.valid, view, report.light.position,
                                    report.radiometry, nominal.target, options.samples);
    } else {
      report.warnings.push_back("light refinement rejected (moved " +
                                std::to_string(Degrees(refined.shift_rad)) +
                                "°): the highlight's light is used");
    }
  }
  {
    StageTimer timer(state->stage_seconds, state->stage_cpu_seconds, "samples", CpuClock::kThread);
    data.directions = ExtractDirectionSamples(hdr.radiance, hdr.valid, hdr.noise_floor, view,
                                              report.light.position, report.radiometry,
                                              nominal.target, options.samples, options.directions);
    data.directions.position = position.index;
  }
  report.theta_in = data.samples.theta_in;
  report.samples = data.samples.pixels_used;
  report.direction_samples = static_cast<int>(data.directions.samples.size());
  const int region = data.directions.pixels_used + data.directions.pixels_below_noise_floor;
  report.below_noise_floor_fraction =
      region > 0 ? static_cast<double>(data.directions.pixels_below_noise_floor) / region : 0;
  if (report.below_noise_floor_fraction > 0.5) {
    report.warnings.push_back(
        Fixed(100 * report.below_noise_floor_fraction, 0) +
        " % of the sample is darker than the sensor's noise floor even in the longest "
        "exposure: that part is not measured (a longer exposure would measure it)");
  }
  report.used = true;
  return data;
}

}  // namespace brdfrig::reconstruct
