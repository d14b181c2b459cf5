// The plots a material scientist reads a BRDF by, for every model the report shows (the fit; the
// truth when the capture is simulated; the glTF version when the material has one):
//   in-plane slices — f in the plane of incidence at several incidence angles θi against the
//     signed viewing angle θo (positive on the mirror side, so the specular peak sits at
//     θo = θi), on a log axis (peak and diffuse floor differ by orders of magnitude), with the
//     measured samples that lie near that plane at about that incidence angle;
//   directional albedo against incidence angle, 0°–85° (brdf::DirectionalAlbedo).
// The value drawn is the mean of the R, G and B channels (the tables elsewhere keep the colour).
// The BrdfFigures (evaluate/brdf_figures.h) hold the error numbers; these are the curves.
// report.json: "figures": {"brdf_plots": {...}}, drawn by BrdfPlotsSection.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "brdf/brdf.h"
#include "brdf/metrics.h"
#include "evaluate/report.h"

namespace brdfrig::evaluate {

struct BrdfPlotOptions {
  std::vector<double> slice_theta_in_deg = {15, 30, 45, 60, 75};  // one plot each, in (0, 90)
  // With measured samples: the slices go where the photos measured the plane of incidence (the
  // whole degrees of θi holding the most in-plane samples, at least min_slice_separation_deg
  // apart, up to max_slices), and slice_theta_in_deg only fills up to min_slices. A plan's
  // photos sit at a few incidence angles; fixed slices would mostly miss them. 10°: one photo
  // spans about ±6° of θi, so closer slices would mostly show the same photo twice.
  bool slices_where_measured = true;
  double min_slice_separation_deg = 10;
  int min_slices = 3, max_slices = 5;
  int min_samples_per_slice = 10;  // an angle with fewer in-plane samples gets no slice of its own
  double theta_out_step_deg = 1;   // the models' curves from −89° to 89°
  // A measured sample is drawn in a slice when its view direction lies within
  // `sample_plane_deg` of that slice's plane of incidence and its incidence angle within
  // `sample_theta_in_deg` of the slice's. One photo spans about ±w/2d ≈ ±6° of θi across a
  // 100 mm cut-out at 0.5 m: 3° keeps a band narrow enough that the samples' peak stays where
  // the curves' is, wide enough to hold a few hundred of them.
  double sample_plane_deg = 3;
  double sample_theta_in_deg = 3;
  int max_samples_per_slice = 400;  // drawn (evenly thinned: thousands of dots slow a browser)
  double albedo_step_deg = 5;       // albedo curve from 0° to 85°
  brdf::MetricOptions albedo_quadrature;
  void Validate() const;  // throws OptionsError
};

// A model drawn: its role ("truth", "fit", "gltf": colours and json keys follow the role) and
// the label in the legend.
struct PlotModel {
  std::string role, label;
  const brdf::Brdf* brdf = nullptr;
};

// A measured BRDF sample in the sample's frame (normal +z): unit directions towards the light and
// the camera, and f (1/sr).
struct MeasuredSample {
  brdf::Vec3 l = brdf::Vec3::UnitZ(), v = brdf::Vec3::UnitZ();
  brdf::Rgb f = brdf::Rgb::Zero();
};

struct BrdfSlice {
  double theta_in_deg = 0;
  std::vector<double> theta_out_deg;   // signed: > 0 on the mirror side
  std::vector<std::vector<double>> f;  // per model (order of BrdfPlots::models), per θo
  // The measured samples near this plane (after thinning), and how many there were before.
  std::vector<double> sample_theta_out_deg, sample_f;
  int samples_near = 0;
};

struct BrdfPlots {
  std::vector<std::pair<std::string, std::string>> models;  // (role, label)
  std::vector<BrdfSlice> slices;
  std::vector<double> albedo_theta_in_deg;
  std::vector<std::vector<double>> albedo;  // per model, per angle
  int samples = 0;                          // measured samples given
  std::string protocol;
};

// The signed in-plane viewing angle of a sample about a slice of incidence angle `theta_in`
// (radians), or NaN when the sample is not near that slice (options' tolerances).
double InPlaneViewAngle(const MeasuredSample& sample, double theta_in,
                        const BrdfPlotOptions& options);

// The slices' incidence angles (degrees, ascending) for these samples (see the options).
std::vector<double> SliceAngles(const std::vector<MeasuredSample>& samples,
                                const BrdfPlotOptions& options);

// Throws OptionsError for bad options, brdfrig::Error for a model without a BRDF or two models
// of one role.
BrdfPlots ComputeBrdfPlots(const std::vector<PlotModel>& models,
                           const std::vector<MeasuredSample>& samples,
                           const BrdfPlotOptions& options = {});

nlohmann::json BrdfPlotsJson(const BrdfPlots& plots);
// The report's section: one log-scale slice plot per incidence angle, then the albedo plot.
ReportSection BrdfPlotsSection(const nlohmann::json& brdf_plots);

}  // namespace brdfrig::evaluate
