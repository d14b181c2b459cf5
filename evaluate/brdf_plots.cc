#include "evaluate/brdf_plots.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/angles.h"
#include "common/error.h"
#include "common/format.h"
#include "evaluate/material_report.h"
#include "evaluate/svg_plot.h"

namespace brdfrig::evaluate {
namespace {

using nlohmann::json;

// Colours and dashes by role, so the same model looks the same in every plot of the report.
Series StyledSeries(const std::string& role, const std::string& label) {
  Series s;
  s.label = label;
  s.markers = false;
  if (role == "truth") {
    s.colour = "#000000";
  } else if (role == "fit") {
    s.colour = "#1f77b4";
  } else if (role == "gltf") {
    s.colour = "#ff7f0e";
    s.dashed = true;
  }
  return s;
}

std::vector<double> Numbers(const json& values) {
  std::vector<double> out;
  for (const json& v : values) out.push_back(NumberFromJson(v));
  return out;
}

json NumbersJson(const std::vector<double>& values) {
  json out = json::array();
  for (double v : values) out.push_back(JsonNumber(v));
  return out;
}

}  // namespace

void BrdfPlotOptions::Validate() const {
  if (slice_theta_in_deg.empty()) throw OptionsError("BRDF plots: slice_theta_in_deg is empty");
  for (double a : slice_theta_in_deg) {
    if (!(a > 0 && a < 90)) {
      throw OptionsError("BRDF plots: slice incidence angle " + Fixed(a, 3) +
                         " deg must be in (0, 90) (at 0° the plane of incidence is undefined)");
    }
  }
  if (!(theta_out_step_deg > 0 && theta_out_step_deg <= 10)) {
    throw OptionsError("BRDF plots: theta_out_step_deg = " + Fixed(theta_out_step_deg, 3) +
                       " must be in (0, 10]");
  }
  if (!(sample_plane_deg > 0 && sample_plane_deg <= 45)) {
    throw OptionsError("BRDF plots: sample_plane_deg = " + Fixed(sample_plane_deg, 3) +
                       " must be in (0, 45]");
  }
  if (!(sample_theta_in_deg > 0 && sample_theta_in_deg <= 45)) {
    throw OptionsError("BRDF plots: sample_theta_in_deg = " + Fixed(sample_theta_in_deg, 3) +
                       " must be in (0, 45]");
  }
  if (max_samples_per_slice < 0) {
    throw OptionsError("BRDF plots: max_samples_per_slice = " +
                       std::to_string(max_samples_per_slice) + " must be >= 0");
  }
  if (!(min_slice_separation_deg >= 2 * sample_theta_in_deg && min_slice_separation_deg <= 45)) {
    throw OptionsError(
        "BRDF plots: min_slice_separation_deg = " + Fixed(min_slice_separation_deg, 3) +
        " must be in [2 · sample_theta_in_deg, 45] (slices would share samples)");
  }
  if (min_slices < 1 || max_slices < min_slices || max_slices > 12) {
    throw OptionsError("BRDF plots: min_slices = " + std::to_string(min_slices) +
                       ", max_slices = " + std::to_string(max_slices) +
                       ": need 1 <= min_slices <= max_slices <= 12");
  }
  if (min_samples_per_slice < 1) {
    throw OptionsError("BRDF plots: min_samples_per_slice = " +
                       std::to_string(min_samples_per_slice) + " must be >= 1");
  }
  if (!(albedo_step_deg >= 1 && albedo_step_deg <= 45)) {
    throw OptionsError("BRDF plots: albedo_step_deg = " + Fixed(albedo_step_deg, 3) +
                       " must be in [1, 45]");
  }
  albedo_quadrature.Validate();
}

double InPlaneViewAngle(const MeasuredSample& sample, double theta_in,
                        const BrdfPlotOptions& options) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const brdf::Vec3 l = sample.l.normalized(), v = sample.v.normalized();
  if (!(l.z() > 0 && v.z() > 0)) return nan;
  if (std::abs(std::acos(std::min(1.0, l.z())) - theta_in) > Radians(options.sample_theta_in_deg))
    return nan;
  // The plane of incidence: the normal and t, the light's direction along the surface (the
  // isotropic material lets every sample's plane be turned onto the slice's).
  const brdf::Vec3 along(l.x(), l.y(), 0);
  if (along.norm() < 1e-9) return nan;
  const brdf::Vec3 t = along.normalized();
  const brdf::Vec3 across(-t.y(), t.x(), 0);
  if (std::asin(std::min(1.0, std::abs(v.dot(across)))) > Radians(options.sample_plane_deg))
    return nan;
  // The mirror direction has v·t = −sin θi: positive angles on that side.
  return std::atan2(-v.dot(t), v.z());
}

std::vector<double> SliceAngles(const std::vector<MeasuredSample>& samples,
                                const BrdfPlotOptions& options) {
  options.Validate();
  std::vector<double> angles;
  auto far_from_chosen = [&](double a) {
    return std::all_of(angles.begin(), angles.end(), [&](double b) {
      return std::abs(a - b) >= options.min_slice_separation_deg;
    });
  };
  if (options.slices_where_measured && !samples.empty()) {
    // In-plane samples per whole degree of θi (the sample's own plane of incidence).
    std::vector<int> count(90, 0);
    for (const MeasuredSample& s : samples) {
      const double theta_in = std::acos(std::clamp(s.l.normalized().z(), -1.0, 1.0));
      const auto degree = static_cast<int>(std::lround(Degrees(theta_in)));
      if (degree < 1 || degree > 88) continue;
      if (std::isfinite(InPlaneViewAngle(s, Radians(degree), options))) ++count[degree];
    }
    while (static_cast<int>(angles.size()) < options.max_slices) {
      int best = -1;
      for (int d = 1; d <= 88; ++d) {
        if (count[d] >= options.min_samples_per_slice && far_from_chosen(d) &&
            (best < 0 || count[d] > count[best])) {
          best = d;
        }
      }
      if (best < 0) break;
      angles.push_back(best);
    }
  }
  // No measured plane of incidence: every default slice; else the defaults only fill up.
  const std::size_t wanted = angles.empty() ? options.slice_theta_in_deg.size()
                                            : static_cast<std::size_t>(options.min_slices);
  for (double a : options.slice_theta_in_deg) {
    if (angles.size() >= wanted) break;
    if (far_from_chosen(a)) angles.push_back(a);
  }
  std::sort(angles.begin(), angles.end());
  return angles;
}

BrdfPlots ComputeBrdfPlots(const std::vector<PlotModel>& models,
                           const std::vector<MeasuredSample>& samples,
                           const BrdfPlotOptions& options) {
  options.Validate();
  BrdfPlots plots;
  for (const PlotModel& m : models) {
    if (m.brdf == nullptr) throw Error("BRDF plots: model '" + m.label + "' has no BRDF");
    for (const auto& [role, label] : plots.models) {
      if (role == m.role) throw Error("BRDF plots: two models with the role '" + m.role + "'");
    }
    plots.models.push_back({m.role, m.label});
  }
  plots.samples = static_cast<int>(samples.size());
  plots.protocol =
      "in-plane slices: light and view in one plane with the normal, θo signed (> 0 on the "
      "mirror side), f the mean of R, G, B (1/sr), log axis; measured samples: view direction "
      "within " +
      Fixed(options.sample_plane_deg, 1) + "° of the plane of incidence and θi within " +
      Fixed(options.sample_theta_in_deg, 1) +
      "° of the slice's; albedo: brdf::DirectionalAlbedo, mean of R, G, B";
  const brdf::Vec3 n = brdf::Vec3::UnitZ();
  const int steps = static_cast<int>(std::floor(89 / options.theta_out_step_deg));
  for (double theta_in_deg : SliceAngles(samples, options)) {
    BrdfSlice slice;
    slice.theta_in_deg = theta_in_deg;
    const double ti = Radians(theta_in_deg);
    const brdf::Vec3 l(std::sin(ti), 0, std::cos(ti));
    for (int i = -steps; i <= steps; ++i)
      slice.theta_out_deg.push_back(i * options.theta_out_step_deg);
    for (const PlotModel& m : models) {
      std::vector<double> f;
      for (double theta_out_deg : slice.theta_out_deg) {
        const double to = Radians(theta_out_deg);
        const brdf::Vec3 v(-std::sin(to), 0, std::cos(to));
        f.push_back(m.brdf->Eval(l, v, n).mean());
      }
      slice.f.push_back(std::move(f));
    }
    std::vector<std::pair<double, double>> near;
    for (const MeasuredSample& s : samples) {
      const double angle = InPlaneViewAngle(s, ti, options);
      if (std::isfinite(angle)) near.push_back({Degrees(angle), s.f.mean()});
    }
    slice.samples_near = static_cast<int>(near.size());
    const std::size_t keep = static_cast<std::size_t>(options.max_samples_per_slice);
    const std::size_t stride = keep == 0 ? 0 : (near.size() + keep - 1) / keep;
    for (std::size_t i = 0; stride > 0 && i < near.size(); i += stride) {
      slice.sample_theta_out_deg.push_back(near[i].first);
      slice.sample_f.push_back(near[i].second);
    }
    plots.slices.push_back(std::move(slice));
  }
  for (double a = 0; a <= 85 + 1e-9; a += options.albedo_step_deg) {
    plots.albedo_theta_in_deg.push_back(a);
  }
  for (const PlotModel& m : models) {
    std::vector<double> albedo;
    for (double a : plots.albedo_theta_in_deg) {
      albedo.push_back(
          brdf::DirectionalAlbedo(*m.brdf, Radians(a), options.albedo_quadrature).mean());
    }
    plots.albedo.push_back(std::move(albedo));
  }
  return plots;
}

json BrdfPlotsJson(const BrdfPlots& plots) {
  json out = {{"protocol", plots.protocol},
              {"models", json::array()},
              {"samples", plots.samples},
              {"slices", json::array()},
              {"albedo", {{"theta_in_deg", plots.albedo_theta_in_deg}}}};
  for (std::size_t m = 0; m < plots.models.size(); ++m) {
    out["models"].push_back({{"role", plots.models[m].first}, {"label", plots.models[m].second}});
    out["albedo"][plots.models[m].first] = NumbersJson(plots.albedo[m]);
  }
  for (const BrdfSlice& s : plots.slices) {
    json j = {{"theta_in_deg", s.theta_in_deg},
              {"theta_out_deg", s.theta_out_deg},
              {"f", json::object()},
              {"samples",
               {{"near", s.samples_near},
                {"theta_out_deg", s.sample_theta_out_deg},
                {"f", NumbersJson(s.sample_f)}}}};
    for (std::size_t m = 0; m < plots.models.size(); ++m) {
      j["f"][plots.models[m].first] = NumbersJson(s.f[m]);
    }
    out["slices"].push_back(j);
  }
  return out;
}

ReportSection BrdfPlotsSection(const json& p) {
  ReportSection s{"BRDF slices and albedo", {}, {}, {}, {}};
  std::vector<std::pair<std::string, std::string>> models;
  for (const json& m : p.at("models")) {
    models.push_back({m.at("role").get<std::string>(), m.at("label").get<std::string>()});
  }
  s.paragraphs.push_back(
      "The BRDF in the plane of incidence at several incidence angles (the specular peak at "
      "θo = θi, the back-scatter side at θo < 0) and the directional albedo against incidence "
      "angle. Protocol: " +
      p.at("protocol").get<std::string>() + ".");
  const int total = p.at("samples").get<int>();
  s.paragraphs.push_back(
      total == 0 ? "No measured samples are drawn (the report was made without the capture's "
                   "samples)."
                 : std::to_string(total) +
                       " measured samples (direction samples of the fitted positions); each "
                       "slice draws those near its plane.");
  Table peaks{
      "In-plane slices: the largest f of each model (1/sr, mean of R, G, B) and the "
      "measured samples near the plane",
      {"theta_in (deg)"},
      {}};
  for (const auto& [role, label] : models) peaks.header.push_back(label + " peak");
  peaks.header.push_back("samples near the plane (drawn)");
  for (const json& slice : p.at("slices")) {
    const double theta_in = slice.at("theta_in_deg").get<double>();
    const std::vector<double> theta_out = slice.at("theta_out_deg").get<std::vector<double>>();
    std::vector<Series> series;
    std::vector<std::string> row = {Fixed(theta_in, 0)};
    for (const auto& [role, label] : models) {
      Series line = StyledSeries(role, label);
      line.x = theta_out;
      line.y = Numbers(slice.at("f").at(role));
      double peak = 0;
      for (double v : line.y) peak = std::isfinite(v) ? std::max(peak, v) : peak;
      row.push_back(Fixed(peak, 4));
      series.push_back(std::move(line));
    }
    const json& samples = slice.at("samples");
    const int near = samples.at("near").get<int>();
    row.push_back(std::to_string(near) + " (" + std::to_string(samples.at("f").size()) + ")");
    peaks.rows.push_back(row);
    if (near > 0) {
      Series dots;
      const std::size_t drawn = samples.at("f").size();
      dots.label = "measured (" + std::to_string(drawn) + ")";  // the table has all of them
      dots.lines = false;
      dots.colour = "#d62728";
      dots.x = samples.at("theta_out_deg").get<std::vector<double>>();
      dots.y = Numbers(samples.at("f"));
      series.push_back(std::move(dots));
    }
    s.svg_plots.push_back(SvgLinePlot(series, {"In-plane BRDF, θi = " + Fixed(theta_in, 0) + "°",
                                               "θo (degrees, > 0 on the mirror side)",
                                               "f (1/sr)",
                                               540,
                                               330,
                                               true,
                                               {-90, -60, -30, 0, 30, 60, 90}}));
  }
  s.tables.push_back(peaks);
  const json& albedo = p.at("albedo");
  std::vector<Series> curves;
  for (const auto& [role, label] : models) {
    Series line = StyledSeries(role, label);
    line.markers = true;
    line.x = albedo.at("theta_in_deg").get<std::vector<double>>();
    line.y = Numbers(albedo.at(role));
    curves.push_back(std::move(line));
  }
  s.svg_plots.push_back(SvgLinePlot(curves, {"Directional albedo against incidence angle",
                                             "θi (degrees)",
                                             "albedo (mean of R, G, B)",
                                             540,
                                             330,
                                             false,
                                             {0, 15, 30, 45, 60, 75, 90}}));
  return s;
}

}  // namespace brdfrig::evaluate
