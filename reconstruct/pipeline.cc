#include "reconstruct/pipeline.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/exr_io.h"
#include "common/format.h"

namespace brdfrig::reconstruct {
namespace {

constexpr double kDeg = 180 / M_PI;

class StageTimer {
 public:
  StageTimer(std::map<std::string, double>* seconds, std::string stage)
      : seconds_(seconds), stage_(std::move(stage)), start_(std::chrono::steady_clock::now()) {}
  ~StageTimer() {
    (*seconds_)[stage_] +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  std::map<std::string, double>* seconds_;
  std::string stage_;
  std::chrono::steady_clock::time_point start_;
};

std::string PositionName(int index) {
  char name[16];
  std::snprintf(name, sizeof(name), "p%02d", index);
  return name;
}

struct LoadedBracket {
  std::vector<cv::Mat> images;
  std::vector<double> exposures;
};

LoadedBracket LoadBracket(const CapturePosition& position, const rig::Intrinsics& intrinsics) {
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
    bracket.images.push_back(std::move(image));
    bracket.exposures.push_back(frame.exposure_s);
  }
  return bracket;
}

// Everything measured at one position before the fit.
struct PositionData {
  PositionReport report;
  BrdfSamples samples;
};

void AppendSamples(BrdfSamples* into, const BrdfSamples& from) {
  const double n_into = static_cast<double>(into->pixels_used);
  const double n_from = static_cast<double>(from.pixels_used);
  into->theta_in =
      (into->theta_in * n_into + from.theta_in * n_from) / std::max(n_into + n_from, 1.0);
  into->theta.insert(into->theta.end(), from.theta.begin(), from.theta.end());
  into->f.insert(into->f.end(), from.f.begin(), from.f.end());
  into->weight.insert(into->weight.end(), from.weight.begin(), from.weight.end());
  into->pixels_used += from.pixels_used;
  into->pixels_invalid += from.pixels_invalid;
  into->theta_in_spread = std::max(into->theta_in_spread, from.theta_in_spread);
  into->angular_pixel_size = std::max(into->angular_pixel_size, from.angular_pixel_size);
}

brdf::SliceDiagnostics Diagnose(const SliceFit& fit, const std::vector<std::string>& extra) {
  brdf::SliceDiagnostics d;
  double residual = 0;
  for (const ChannelFit& c : fit.channel) residual += c.rms_log_residual / 3;
  d.residual = residual;
  d.sample_count = fit.sample_count;
  d.theta_min = fit.theta_min;
  d.theta_max = fit.theta_max;
  d.has_stddev = true;
  for (int c = 0; c < 3; ++c) d.stddev[c] = fit.channel[c].stddev;
  d.warnings = extra;
  d.warnings.insert(d.warnings.end(), fit.warnings.begin(), fit.warnings.end());
  return d;
}

}  // namespace

void ReconstructOptions::Validate() const {
  hdr.Validate();
  target.Validate();
  light.Validate();
  light_refine.Validate();
  radiometry.Validate();
  samples.Validate();
  fit.Validate();
}

ReconstructionResult Reconstruct(const CaptureSet& capture, const ReconstructOptions& options,
                                 const ProgressCallback& progress) {
  options.Validate();
  const auto say = [&](const std::string& message) {
    if (progress) progress(message);
  };
  ReconstructionResult result;
  result.warnings = capture.warnings;
  for (const std::string& w : capture.warnings) say("warning: " + w);
  auto& seconds = result.stage_seconds;
  const rig::RigGeometry& nominal = capture.nominal;
  if (!options.hdr_dir.empty()) std::filesystem::create_directories(options.hdr_dir);

  std::vector<const CapturePosition*> positions;
  for (const CapturePosition& p : capture.positions) {
    if (p.validation) {
      result.validation.push_back(p);  // never fitted
      continue;
    }
    if (options.use_positions.empty() ||
        std::find(options.use_positions.begin(), options.use_positions.end(), p.index) !=
            options.use_positions.end()) {
      positions.push_back(&p);
    }
  }
  if (positions.empty()) throw Error(capture.name + ": no capture positions to reconstruct from");

  cv::Mat response;  // recovered once per capture for non-linear (8-bit) photos
  std::vector<PositionData> measured;
  HdrImage hdr;  // one buffer for every position's merge (each position is done with it)
  for (const CapturePosition* position : positions) {
    PositionData data;
    PositionReport& report = data.report;
    report.index = position->index;
    const std::string name = PositionName(position->index);
    say(name + ": merging " + std::to_string(position->frames.size()) + " exposures");
    try {
      LoadedBracket bracket;
      {
        StageTimer timer(&seconds, "load");
        bracket = LoadBracket(*position, nominal.intrinsics);
      }
      {
        StageTimer timer(&seconds, "hdr");
        if (bracket.images[0].depth() == CV_8U && response.empty()) {
          response = RecoverResponse(bracket.images, bracket.exposures);
        }
        MergeBracketInto(bracket.images, bracket.exposures, response, &hdr, options.hdr);
      }
      report.invalid_fraction = hdr.invalid_fraction;
      if (!options.hdr_dir.empty()) {
        StageTimer timer(&seconds, "write");
        WriteRadianceExr(options.hdr_dir / (name + ".exr"), hdr.radiance);
        std::vector<std::uint8_t> png;
        cv::imencode(".png", hdr.valid, png);
        WriteFileAtomically(options.hdr_dir / (name + "_valid.png"),
                            std::string(png.begin(), png.end()));
      }
      const rig::CameraPose nominal_pose = nominal.CameraAt(position->axis_readings);
      PoseEstimate pose;
      {
        StageTimer timer(&seconds, "target");
        const TargetCorners corners =
            FindCutoutCorners(hdr.radiance, hdr.valid, nominal.intrinsics, nominal_pose,
                              nominal.target, options.target);
        pose =
            EstimatePose(corners, nominal.intrinsics, nominal.target, nominal_pose, options.target);
      }
      report.reprojection_rms_px = pose.reprojection_rms_px;
      report.camera_disagreement_m = pose.nominal_disagreement_m;
      if (pose.nominal_disagreement_m > options.target.warn_camera_offset_m) {
        report.warnings.push_back(
            "camera pose " + Fixed(pose.nominal_disagreement_m * 1e3, 1) +
            " mm from the rig's nominal: check the rig file, or the cut-out's "
            "edges in badly exposed photos");
      }
      const PlaneView view(nominal.intrinsics, pose.pose);
      {
        StageTimer timer(&seconds, "light");
        report.light = EstimateLight(hdr.radiance, hdr.valid, view, nominal.target,
                                     nominal.LightAt(position->axis_readings), options.light);
      }
      for (const std::string& w : report.light.warnings) report.warnings.push_back(w);
      {
        StageTimer timer(&seconds, "radiometry");
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
        StageTimer timer(&seconds, "samples");
        data.samples = ExtractSamples(hdr.radiance, hdr.valid, view, report.light.position,
                                      report.radiometry, nominal.target, options.samples);
      }
      if (data.samples.theta.size() < 16) {
        throw Error("only " + std::to_string(data.samples.pixels_used) + " usable sample pixels (" +
                    std::to_string(data.samples.pixels_invalid) +
                    " clipped in every exposure): add a shorter exposure");
      }
      if (report.light.from_highlight && options.light_refine.enabled) {
        StageTimer timer(&seconds, "light");
        const LightRefinement refined = RefineLight(
            hdr.radiance, hdr.valid, view, nominal.target, options.samples, report.light.position,
            report.radiometry, FitSlice(data.samples, options.fit), options.light_refine);
        if (refined.accepted) {
          report.light_refinement_rad = refined.shift_rad;
          report.light.position = refined.position;
          const rig::Vec3 nominal_light = nominal.LightAt(position->axis_readings);
          const rig::Vec3 at = report.light.highlight_in_world;
          const rig::Vec3 a = refined.position - at, b = nominal_light - at;
          report.light.nominal_disagreement_rad = std::atan2(a.cross(b).norm(), a.dot(b));
          report.radiometry =
              CalibrateFromPaper(hdr.radiance, hdr.valid, view, report.light.position,
                                 nominal.target, options.radiometry);
          data.samples = ExtractSamples(hdr.radiance, hdr.valid, view, report.light.position,
                                        report.radiometry, nominal.target, options.samples);
        } else {
          report.warnings.push_back("light refinement rejected (moved " +
                                    std::to_string(refined.shift_rad * kDeg) +
                                    "°): the highlight's light is used");
        }
      }
      report.theta_in = data.samples.theta_in;
      report.samples = data.samples.pixels_used;
      report.used = true;
      measured.push_back(std::move(data));
    } catch (const Error& e) {
      report.used = false;
      report.skipped_reason = e.what();
      result.warnings.push_back(name + " skipped: " + e.what());
      say(name + " skipped: " + e.what());
      result.positions.push_back(report);
    }
  }
  if (measured.empty()) {
    std::string reasons;
    for (const PositionReport& r : result.positions) reasons += "\n  " + r.skipped_reason;
    throw Error(capture.name + ": no position could be reconstructed:" + reasons);
  }

  // One slice per incidence angle: positions at the same theta_in (within 0.1°) pool their
  // samples, so the knots stay strictly increasing.
  std::sort(measured.begin(), measured.end(), [](const PositionData& a, const PositionData& b) {
    return a.samples.theta_in < b.samples.theta_in;
  });
  struct SliceInput {
    BrdfSamples samples;
    std::vector<std::string> warnings;
    std::vector<int> positions;
  };
  std::vector<SliceInput> inputs;
  for (PositionData& data : measured) {
    if (!inputs.empty() && data.samples.theta_in - inputs.back().samples.theta_in < 0.1 / kDeg) {
      AppendSamples(&inputs.back().samples, data.samples);
      inputs.back().warnings.push_back("positions pooled: same incidence angle");
    } else {
      inputs.push_back({std::move(data.samples), {}, {}});
    }
    for (const std::string& w : data.report.warnings) inputs.back().warnings.push_back(w);
    inputs.back().positions.push_back(data.report.index);
    result.positions.push_back(data.report);
  }
  // Reports in capture order, skipped and used alike.
  std::sort(result.positions.begin(), result.positions.end(),
            [](const PositionReport& a, const PositionReport& b) { return a.index < b.index; });

  std::vector<SliceFit> fits;
  {
    StageTimer timer(&seconds, "fit");
    for (const SliceInput& input : inputs) {
      say("fitting the slice at theta_in " + std::to_string(input.samples.theta_in * kDeg) + "°");
      fits.push_back(FitSlice(input.samples, options.fit));
    }
    // A slice whose samples never reach the lobe's tail cannot tell A2: it takes the median A2
    // of the slices that can (the floor is mostly diffuse and varies slowly with theta_in).
    std::array<std::vector<double>, 3> observed_a2;
    for (const SliceFit& fit : fits) {
      if (!fit.a2_observed) continue;
      for (int c = 0; c < 3; ++c) observed_a2[c].push_back(fit.channel[c].params.a2);
    }
    for (std::size_t i = 0; i < fits.size(); ++i) {
      if (fits[i].a2_observed) continue;
      if (observed_a2[0].empty()) {
        fits[i].warnings.push_back("no slice reaches the lobe's tail: A2 is an extrapolation");
        continue;
      }
      std::array<double, 3> shared{};
      for (int c = 0; c < 3; ++c) {
        std::vector<double> v = observed_a2[c];
        std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
        shared[c] = v[v.size() / 2];
      }
      fits[i] = FitSlice(inputs[i].samples, options.fit, shared);
      fits[i].warnings.push_back("A2 shared across slices: median of the " +
                                 std::to_string(observed_a2[0].size()) +
                                 " slices whose samples reach the tail");
    }
  }

  brdf::Material& material = result.material;
  nlohmann::json provenance = {{"software", std::string("brdfrig ") + BRDFRIG_VERSION},
                               {"source", capture.name},
                               {"method", "per-position logistic slices, Ceres LM, log residuals"}};
  nlohmann::json used = nlohmann::json::array();
  for (std::size_t i = 0; i < fits.size(); ++i) {
    material.slices.push_back(fits[i].slice);
    material.diagnostics.push_back(Diagnose(fits[i], inputs[i].warnings));
    used.push_back({{"theta_in", fits[i].slice.theta_in}, {"positions", inputs[i].positions}});
  }
  provenance["slices_from_positions"] = used;
  nlohmann::json positions_json = nlohmann::json::array();
  for (const PositionReport& r : result.positions) {
    nlohmann::json p = {{"index", r.index}, {"used", r.used}};
    if (!r.used) {
      p["skipped"] = r.skipped_reason;
    } else {
      p["reprojection_rms_px"] = r.reprojection_rms_px;
      p["light_from_highlight"] = r.light.from_highlight;
      p["light_vs_nominal_deg"] = r.light.nominal_disagreement_rad * kDeg;
      p["light_refinement_deg"] = r.light_refinement_rad * kDeg;
      p["camera_vs_nominal_m"] = r.camera_disagreement_m;
      p["paper_spread"] = r.radiometry.relative_spread;
      p["clipped_fraction"] = r.invalid_fraction;
    }
    positions_json.push_back(p);
  }
  provenance["positions"] = positions_json;
  material.provenance = provenance;
  // Validates the result like any reader would: a fit must never write an invalid model.
  (void)material.Model();
  return result;
}

std::string ReconstructionResult::Summary() const {
  std::ostringstream out;
  out.setf(std::ios::fixed);
  out.precision(3);
  out << "positions:\n";
  for (const PositionReport& p : positions) {
    out << "  " << PositionName(p.index) << ": ";
    if (!p.used) {
      out << "skipped (" << p.skipped_reason << ")\n";
      continue;
    }
    out << "theta_in " << p.theta_in * kDeg << "°, pose reprojection " << p.reprojection_rms_px
        << " px (edges " << p.edge_line_rms_px << " px), camera " << p.camera_disagreement_m * 1000
        << " mm from nominal, light " << (p.light.from_highlight ? "from highlight" : "nominal")
        << " (" << p.light.nominal_disagreement_rad * kDeg << "° from nominal, refined by "
        << p.light_refinement_rad * kDeg << "°), paper spread " << p.radiometry.relative_spread
        << ", " << p.samples << " samples\n";
  }
  out << "slices (R, G, B: A1 A2 h x0; angles in degrees):\n";
  for (std::size_t i = 0; i < material.slices.size(); ++i) {
    const brdf::Slice& s = material.slices[i];
    out << "  theta_in " << s.theta_in * kDeg << "°:";
    for (const brdf::LobeParams& p : s.channel) {
      out << "  [" << p.a1 << " " << p.a2 << " " << p.h * kDeg << " " << p.x0 * kDeg << "]";
    }
    out << "  residual " << material.diagnostics[i].residual << "\n";
    for (const std::string& w : material.diagnostics[i].warnings)
      out << "    warning: " << w << "\n";
  }
  for (const std::string& w : warnings) out << "warning: " << w << "\n";
  out << "time:";
  for (const auto& [stage, s] : stage_seconds) out << " " << stage << " " << s << " s";
  out << "\n";
  return out.str();
}

}  // namespace brdfrig::reconstruct
