#include "reconstruct/pipeline.h"
#include "common/angles.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <map>
#include <mutex>
#include <optional>
#include <sstream>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/format.h"
#include "common/parallel.h"
#include "common/sha256.h"
#include "reconstruct/gain_map.h"
#include "reconstruct/stage_timer.h"

namespace brdfrig::reconstruct {
namespace {

bool Contains(const std::vector<int>& list, int index) {
  return std::find(list.begin(), list.end(), index) != list.end();
}

const char* MethodOf(brdf::ModelKind kind) {
  switch (kind) {
    case brdf::ModelKind::kSeed:
      return "per-position logistic slices, Ceres LM, log residuals";
    case brdf::ModelKind::kSeedConstrained:
      return "per-position logistic slices sharing one measured diffuse level, energy-limited";
    case brdf::ModelKind::kMicrofacet:
      return "data-driven microfacet (monotone ln D table, GGX tail, Smith G, Schlick F with "
             "theta_d correction), one fit over every position, Ceres LM, log(eps + f cos) loss";
    case brdf::ModelKind::kGgx:
    case brdf::ModelKind::kBeckmann:
      return "analytic microfacet + Lambert, one fit over every position, Ceres LM, "
             "log(eps + f cos) loss";
    case brdf::ModelKind::kPrior:
      return "Rusinkiewicz table: maximum a posteriori coefficients of the measured prior's "
             "principal components in ln(f c + eps), corrected towards the samples where the "
             "photos saw the material";
    case brdf::ModelKind::kGltf:
      return "glTF 2.0 metal-rough BRDF (not a rung)";
  }
  return "?";
}

// A frame whose content differs from what the capture recorded (edited, truncated, bit rot)
// must not be fitted as if it were the measurement.
void VerifyRecordedHashes(const CapturePosition& position) {
  for (const BracketFrame& frame : position.frames) {
    if (frame.sha256.empty()) continue;
    if (!std::filesystem::exists(frame.file)) {
      throw FileError(frame.file.string(), "recorded photo is missing");
    }
    if (Sha256FileHex(frame.file) != frame.sha256) {
      throw FileError(frame.file.string(),
                      "SHA-256 differs from the one recorded at capture (the photo changed "
                      "since; `brdfrig session verify` lists every such file)");
    }
  }
}

// Why a used position's result is degraded ("" when it is not): its photos held NaN or
// infinite pixels (a corrupt or badly converted float image), masked as invalid, which near
// the highlight cost the pose and light estimates accuracy nothing else reports; or its whole
// sample was darker than the sensor's noise floor even in the longest exposure, so it measured
// the material nowhere (its pose and paper still count, its BRDF samples do not).
std::string DegradedReason(const PositionReport& report) {
  std::string reason;
  if (report.non_finite_pixels > 0) {
    reason = std::to_string(report.non_finite_pixels) +
             " NaN or infinite pixels in its photos (masked as invalid)";
  }
  if (report.direction_samples == 0 && report.below_noise_floor_fraction > 0) {
    if (!reason.empty()) reason += "; ";
    reason +=
        "its whole sample is darker than the sensor's noise floor in the longest exposure "
        "(nothing measured; a longer exposure would measure it)";
  }
  return reason;
}

// The longest exposure of any position's bracket (seconds), for the message that asks for a
// longer one.
double LongestExposure(const CaptureSet& capture) {
  double longest = 0;
  for (const CapturePosition& p : capture.positions) {
    for (const BracketFrame& f : p.frames) longest = std::max(longest, f.exposure_s);
  }
  return longest;
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
  directions.Validate();
  microfacet.Validate();
  gltf.Validate();
  if (!model.empty()) (void)brdf::ParseModelKind(model);
  if (!model.empty() && brdf::ParseModelKind(model) == brdf::ModelKind::kGltf) {
    throw OptionsError(
        "ReconstructOptions.model = gltf; not a rung of the ladder (the glTF "
        "version of the chosen rung is written with every material)");
  }
}

nlohmann::json ReconstructOptions::ResultKey() const {
  const MicrofacetFitOptions& m = microfacet;
  return {{"model", model},
          {"validate", validate},
          {"use_positions", use_positions},
          {"validation_positions", validation_positions},
          {"hdr", {hdr.saturation, hdr.read_floor, hdr.noise_floor}},
          {"target",
           {target.search_band, target.corner_skip, target.profile_step_px, target.min_log_step,
            target.min_edge_fraction, target.use_paper_outline, target.lines_per_edge,
            target.max_reprojection_px, target.warn_camera_offset_m}},
          {"light",
           {light.smoothing_px, light.min_peak_ratio, light.edge_inset,
            light.max_nominal_disagreement_deg}},
          {"light_refine",
           {light_refine.enabled, light_refine.max_pixels, light_refine.max_iterations,
            light_refine.max_shift_rad}},
          {"radiometry",
           {radiometry.margin, radiometry.stride, radiometry.warn_spread, radiometry.flat_field}},
          {"samples", {samples.edge_margin, samples.bin_width}},
          {"fit",
           {fit.max_iterations, fit.function_tolerance, fit.parameter_tolerance, fit.loss_scale,
            fit.covariance}},
          {"directions",
           {directions.max_block_px, directions.min_theta_h_span, directions.relative_theta_h_span,
            directions.max_theta_d_span}},
          {"microfacet",
           {m.table_knots, m.fresnel_knots, m.fresnel_prior, m.smoothness, m.epsilon_fraction,
            m.loss_scale, m.max_iterations, m.covariance, m.energy_check}},
          {"prior",
           {prior.prior == nullptr ? std::string("shipped") : "custom " + prior.prior->name,
            prior.fit.misfit_limit, prior.fit.correct}},
          {"gltf",
           {gltf.source, gltf.theta_h_steps, gltf.theta_d_steps, gltf.phi_d_steps,
            gltf.epsilon_fraction, gltf.loss_scale, gltf.max_iterations, gltf.sphere.resolution,
            gltf.sphere.light_angles_deg}}};
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
  if (!options.hdr_dir.empty()) CreateDirectories(options.hdr_dir);

  // Stage 1: measure every position. Validation positions (the plan's, or named in the
  // options) are measured to score the ladder's rungs, never fitted.
  MeasureOptions measure{options.hdr,          options.target,     options.light,
                         options.light_refine, options.radiometry, options.samples,
                         options.directions,   options.fit,        options.hdr_dir};
  if (capture.calibration && !capture.calibration->light.empty()) {
    measure.light.use_highlight = false;
  }
  std::vector<PositionSamples> fit_positions, validation_positions;
  for (const CaptureSet::LeftOut& left : capture.left_out) {
    if (!options.use_positions.empty() && !Contains(options.use_positions, left.index)) continue;
    PositionReport report;
    report.index = left.index;
    report.skipped_reason = left.reason;
    result.positions.push_back(report);
  }
  // The positions to measure, in capture order; each is measured into its own slot.
  struct Measured {
    const CapturePosition* position = nullptr;
    bool validation = false;
    std::optional<MeasuredPosition> data;
    std::string skipped;  // why it could not be measured
    std::map<std::string, double> seconds, cpu_seconds;
  };
  std::vector<Measured> measured;
  for (const CapturePosition& position : capture.positions) {
    const bool validation =
        position.validation || Contains(options.validation_positions, position.index);
    if (position.validation) result.validation.push_back(position);
    if (!options.use_positions.empty() && !Contains(options.use_positions, position.index) &&
        !validation) {
      continue;
    }
    measured.push_back({&position, validation, std::nullopt, {}, {}, {}});
  }
  std::mutex say_mutex;
  const auto measure_one = [&](Measured& m, MeasureState* state) {
    const std::string name = PositionName(m.position->index);
    {
      std::lock_guard lock(say_mutex);
      say(name + ": merging " + std::to_string(m.position->frames.size()) + " exposures");
    }
    state->stage_seconds = &m.seconds;
    state->stage_cpu_seconds = &m.cpu_seconds;
    try {
      VerifyRecordedHashes(*m.position);
      m.data = MeasurePosition(*m.position, capture.nominal, measure, state);
    } catch (const OutputError&) {
      throw;  // a debug file that cannot be written fails the run, never drops the position
    } catch (const Error& e) {
      m.skipped = e.what();
      std::lock_guard lock(say_mutex);
      say(name + " skipped: " + e.what());
    }
  };
  // Positions are independent once the photos' response is known (8-bit photos: recovered from
  // the first bracket merged, and shared by the rest): measured one by one until a bracket has
  // been merged, then the rest on every thread, each with its own copy of that state (its own
  // HDR buffer). The results are those of measuring them in order. (A capture that mixed
  // linear and 8-bit brackets, a linear one first, would recover the response once per thread.)
  std::size_t next = 0;
  {
    StageTimer timer(&result.stage_seconds, &result.stage_cpu_seconds, "measure");
    MeasureState state;
    if (capture.calibration && !capture.calibration->flat.empty()) {
      state.gain = ReadGainMap(capture.calibration->flat, capture.nominal.intrinsics);
    }
    while (next < measured.size() && !state.merged) measure_one(measured[next++], &state);
    std::atomic<std::size_t> claim = next;
    const std::size_t rest = measured.size() - next;
    const int workers = static_cast<int>(std::min<std::size_t>(rest, DefaultThreadCount()));
    if (rest > 0) {
      ParallelFor(
          static_cast<std::size_t>(workers),
          [&](std::size_t begin, std::size_t end) {
            for (std::size_t w = begin; w < end; ++w) {
              MeasureState own;
              own.gain = state.gain;
              own.response = state.response;
              own.merged = state.merged;
              for (std::size_t i = claim++; i < measured.size(); i = claim++) {
                measure_one(measured[i], &own);
              }
            }
          },
          workers);
    }
  }
  for (Measured& m : measured) {
    for (const auto& [stage, s] : m.seconds) result.stage_seconds[stage] += s;
    for (const auto& [stage, s] : m.cpu_seconds) result.stage_cpu_seconds[stage] += s;
    if (!m.data) {
      PositionReport report;
      report.index = m.position->index;
      report.skipped_reason = m.skipped;
      result.warnings.push_back(PositionName(m.position->index) + " skipped: " + m.skipped);
      result.positions.push_back(report);
      continue;
    }
    MeasuredPosition& data = *m.data;
    PositionSamples samples{m.position->index, std::move(data.samples), std::move(data.directions),
                            data.report.warnings};
    (m.validation ? validation_positions : fit_positions).push_back(std::move(samples));
    result.positions.push_back(std::move(data.report));
  }
  if (result.positions.empty()) {
    throw Error(capture.name + ": no capture positions to reconstruct from");
  }
  std::sort(result.positions.begin(), result.positions.end(),
            [](const PositionReport& a, const PositionReport& b) { return a.index < b.index; });
  if (options.strict) {
    std::vector<std::string> incomplete = result.Dropped();
    for (const std::string& d : result.Degraded()) incomplete.push_back(d);
    if (!incomplete.empty()) {
      std::string reasons;
      for (const std::string& d : incomplete) reasons += "\n  " + d;
      throw Error(
          capture.name + ": " + std::to_string(incomplete.size()) +
          " position(s) dropped or degraded, refused under --strict (nothing written):" + reasons);
    }
  }
  if (fit_positions.empty()) {
    std::string reasons;
    for (const PositionReport& r : result.positions) reasons += "\n  " + r.skipped_reason;
    throw Error(capture.name + ": no position could be reconstructed:" + reasons);
  }
  // A sample too dark for the bracket everywhere: every rung would fit read noise.
  if (std::all_of(fit_positions.begin(), fit_positions.end(),
                  [](const PositionSamples& p) { return p.directions.samples.empty(); }) &&
      std::any_of(result.positions.begin(), result.positions.end(),
                  [](const PositionReport& r) { return r.below_noise_floor_fraction > 0; })) {
    throw Error(capture.name + ": the sample is darker than the sensor's noise floor (" +
                Fixed(options.hdr.noise_floor * 100, 2) +
                " % of full scale) at every position, even in the longest exposure (" +
                Fixed(LongestExposure(capture), 4) +
                " s): nothing was measured. Lengthen the bracket (the plan's `exposures:`, or "
                "auto-bracketing's `longest_max_s`) until the sample reads above the floor.");
  }

  // Stages 2–3: every rung of the ladder, scored on what it was not fitted to.
  LadderOptions ladder_options;
  ladder_options.model = options.model;
  ladder_options.slice = options.fit;
  ladder_options.microfacet = options.microfacet;
  ladder_options.prior = options.prior;
  ladder_options.validate = options.validate;
  {
    StageTimer timer(&result.stage_seconds, &result.stage_cpu_seconds, "fit");
    result.ladder = FitLadder(fit_positions, validation_positions, ladder_options, say);
  }
  const RungResult& chosen = result.ladder.rungs[result.ladder.chosen];
  for (const std::string& w : chosen.warnings) result.warnings.push_back(w);

  brdf::Material& material = result.material;
  material = chosen.material;
  material.ladder = result.ladder.Json();
  nlohmann::json provenance = {{"software", std::string("brdfrig ") + BRDFRIG_VERSION},
                               {"source", capture.name},
                               {"method", MethodOf(material.kind)},
                               {"options", options.ResultKey()}};
  if (brdf::IsSliceKind(material.kind)) {
    provenance["slices_from_positions"] = chosen.slices_from_positions;
  }
  nlohmann::json positions_json = nlohmann::json::array();
  for (const PositionReport& r : result.positions) {
    const bool validation =
        Contains(options.validation_positions, r.index) ||
        std::any_of(result.validation.begin(), result.validation.end(),
                    [&](const CapturePosition& v) { return v.index == r.index; });
    nlohmann::json p = {{"index", r.index}, {"used", r.used}, {"validation", validation}};
    if (!r.used) {
      p["skipped"] = r.skipped_reason;
    } else {
      if (!r.warnings.empty()) p["warnings"] = r.warnings;
      p["non_finite_pixels"] = r.non_finite_pixels;
      if (const std::string reason = DegradedReason(r); !reason.empty()) p["degraded"] = reason;
      p["pose_from"] = r.pose_from;
      p["pose_points"] = r.pose_points;
      p["reprojection_rms_px"] = r.reprojection_rms_px;
      p["light_from"] = r.light.Source();
      p["light_vs_nominal_deg"] = Degrees(r.light.nominal_disagreement_rad);
      p["light_refinement_deg"] = Degrees(r.light_refinement_rad);
      p["camera_vs_nominal_m"] = r.camera_disagreement_m;
      p["paper_spread"] = r.radiometry.relative_spread;
      p["clipped_fraction"] = r.invalid_fraction;
      p["direction_samples"] = r.direction_samples;
      p["below_noise_floor_fraction"] = r.below_noise_floor_fraction;
    }
    positions_json.push_back(p);
  }
  provenance["positions"] = positions_json;
  provenance["dropped_positions"] = result.Dropped().size();
  provenance["degraded_positions"] = result.Degraded().size();
  // The sample's size for the glTF export's tile (reconstruct/gltf_export.h).
  provenance["cutout_m"] = {capture.nominal.target.cutout_width,
                            capture.nominal.target.cutout_height};
  // What the reconstruction trusted about the rig: each calibration's file and hash, or the
  // nominal values it ran on instead (docs/calibration.md).
  if (capture.calibration) {
    provenance["calibration"] = capture.calibration->Provenance();
    const std::string nominal = capture.calibration->NominalOnes();
    if (!nominal.empty()) {
      result.warnings.push_back("ran on the rig's nominal values for: " + nominal +
                                " (no calibration in rig.yaml's `calibration:`; "
                                "docs/calibration.md)");
    }
  }
  material.provenance = provenance;
  // The chosen rung's glTF version and what exporting it costs (docs/gltf.md).
  {
    const auto start = std::chrono::steady_clock::now();
    StageTimer timer(nullptr, &result.stage_cpu_seconds, "gltf");
    AddGltfVersion(&material, options.gltf,
                   options.gltf.source == "samples" ? PoolDirectionSamples(fit_positions)
                                                    : std::vector<DirectionSample>{});
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    result.stage_seconds["gltf"] += seconds;
    say("glTF version: " + material.gltf_fit["sphere_vs_model"]["mean_psnr_db"].dump() +
        " dB sphere PSNR against the " + brdf::ModelKindName(material.kind) + " rung (" +
        Fixed(seconds, 2) + " s)");
  }
  // Validates the result like any reader would: a fit must never write an invalid model.
  (void)material.Model();
  return result;
}

std::vector<std::string> ReconstructionResult::Degraded() const {
  std::vector<std::string> degraded;
  for (const PositionReport& p : positions) {
    const std::string reason = p.used ? DegradedReason(p) : "";
    if (!reason.empty()) degraded.push_back(PositionName(p.index) + ": " + reason);
  }
  return degraded;
}

std::vector<std::string> ReconstructionResult::Dropped() const {
  std::vector<std::string> dropped;
  for (const PositionReport& p : positions) {
    if (!p.used) dropped.push_back(PositionName(p.index) + ": " + p.skipped_reason);
  }
  return dropped;
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
    out << "theta_in " << Degrees(p.theta_in) << "°, pose from the " << p.pose_from << " ("
        << p.pose_points << " points), reprojection " << p.reprojection_rms_px << " px";
    if (p.pose_from == "cut-out") out << " (edges " << p.edge_line_rms_px << " px)";
    out << ", camera " << p.camera_disagreement_m * 1000 << " mm from nominal, light "
        << (p.light.from_highlight ? "from highlight" : "nominal") << " ("
        << Degrees(p.light.nominal_disagreement_rad) << "° from nominal, refined by "
        << Degrees(p.light_refinement_rad) << "°), paper spread " << p.radiometry.relative_spread
        << ", " << p.samples << " samples (" << p.direction_samples << " with directions)\n";
  }
  out << "model: " << brdf::ModelKindName(material.kind) << "\n";
  out << ladder.Summary();
  if (!brdf::IsSliceKind(material.kind)) {
    const brdf::MicrofacetModelParams& m = material.microfacet;
    out << "  rho_d " << m.diffuse.transpose() << ", f0 " << m.f0.transpose() << ", alpha "
        << m.alpha;
    if (m.distribution == brdf::Distribution::kTable) {
      out << " (tail), shadowing alpha " << m.shadowing_alpha << ", " << m.log_d.size()
          << " knots to theta_h " << Degrees(m.max_theta_h) << "°";
    }
    out << ", residual " << material.fit.value("residual", 0.0) << "\n";
    for (const auto& w : material.fit.value("warnings", nlohmann::json::array())) {
      out << "    warning: " << w.get<std::string>() << "\n";
    }
  } else {
    out << "slices (R, G, B: A1 A2 h x0; angles in degrees):\n";
  }
  for (std::size_t i = 0; i < material.slices.size() && brdf::IsSliceKind(material.kind); ++i) {
    const brdf::Slice& s = material.slices[i];
    out << "  theta_in " << Degrees(s.theta_in) << "°:";
    for (const brdf::LobeParams& p : s.channel) {
      out << "  [" << p.a1 << " " << p.a2 << " " << Degrees(p.h) << " " << Degrees(p.x0) << "]";
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
