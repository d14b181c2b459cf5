#include "acquire/plan_check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>

#include "common/angles.h"

namespace brdfrig::acquire {
namespace {

std::string At(const Plan& plan, int line) { return plan.file + ":" + std::to_string(line) + ": "; }

std::string Deg(double radians) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f°", Degrees(radians));
  return text;
}

geometry::Vec3 Reflect(const geometry::Vec3& l, const geometry::Vec3& n) {
  return 2 * n.dot(l) * n - l;
}

// Where the camera sees the light's mirror image in the plane z = 0, and what that means.
void CheckHighlight(const geometry::RigGeometry& g, const geometry::AxisPositions& axes,
                    PositionCheck* c) {
  const geometry::CameraPose pose = g.CameraAt(axes);
  const geometry::Vec3 camera = pose.CenterInWorld();
  const geometry::Vec3 light = g.LightAt(axes);
  if (camera.z() <= 0 || light.z() <= 0) return;  // below the sample plane: no highlight
  // The mirror image of the light is below the plane; the ray to it crosses z = 0 at the
  // mirror point.
  const geometry::Vec3 mirrored(light.x(), light.y(), -light.z());
  const double t = camera.z() / (camera.z() + light.z());
  const geometry::Vec3 p = camera + t * (mirrored - camera);
  c->highlight_x = p.x();
  c->highlight_y = p.y();
  const geometry::Vec3 n = geometry::Vec3::UnitZ();
  c->theta_in = std::acos(std::clamp((light - p).normalized().dot(n), -1.0, 1.0));
  const bool in_cutout =
      std::abs(p.x()) <= g.target.cutout_width / 2 && std::abs(p.y()) <= g.target.cutout_height / 2;
  Eigen::Vector2d pixel;
  const bool projects = geometry::ProjectToPixel(g.intrinsics, pose, p, &pixel) && pixel.x() >= 0 &&
                        pixel.y() >= 0 && pixel.x() < g.intrinsics.width &&
                        pixel.y() < g.intrinsics.height;
  if (projects) {
    c->highlight_u = pixel.x();
    c->highlight_v = pixel.y();
  }
  c->highlight_visible = in_cutout && projects;
  // The angle from the mirror direction grows towards the cut-out's corners: its largest value
  // tells how far from the lobe peak this photo reaches (docs/design.md, capture geometry).
  for (const double sx : {-0.5, 0.5}) {
    for (const double sy : {-0.5, 0.5}) {
      const geometry::Vec3 x(sx * g.target.cutout_width, sy * g.target.cutout_height, 0);
      const geometry::Vec3 v = (camera - x).normalized();
      const geometry::Vec3 r = Reflect((light - x).normalized(), n);
      c->theta_max = std::max(c->theta_max, std::acos(std::clamp(v.dot(r), -1.0, 1.0)));
    }
  }
}

}  // namespace

double EstimateMoveS(double distance, const TimingAssumptions& timing) {
  const double d = std::abs(distance);
  const double v = timing.axis_speed, a = timing.axis_acceleration;
  if (d * a <= v * v) return 2.0 * std::sqrt(d / a);
  return d / v + v / a;
}

PlanCheckReport CheckPlan(const Plan& plan_in, const geometry::RigDescription& rig,
                          const TimingAssumptions& timing) {
  PlanCheckReport report;
  const geometry::RigGeometry& g = rig.geometry;
  Plan plan = plan_in;
  try {
    if (const auto design = ResolvePlan(&plan, g)) report.design = design->ToString();
  } catch (const Error& e) {
    report.errors.push_back(e.what());
    return report;
  }
  report.resolved = plan.positions;
  report.bracket_s = plan.exposures_s;
  geometry::AxisPositions previous;  // axes start where homing leaves them: 0
  for (const geometry::RotationAxis& axis : g.axes) previous[axis.name] = 0;
  const int shots = plan.BracketSize();
  for (std::size_t i = 0; i < plan.positions.size(); ++i) {
    const PlannedPosition& planned = plan.positions[i];
    PositionCheck check;
    check.index = static_cast<int>(i);
    check.line = planned.line;
    for (const auto& [name, angle] : planned.axes) {
      const geometry::RotationAxis* axis = g.FindAxis(name);
      if (axis == nullptr) {
        report.errors.push_back(At(plan, planned.line) + "position " + std::to_string(i) +
                                ": the rig (" + rig.file.string() + ") has no axis '" + name + "'");
        check.reachable = false;
        continue;
      }
      if (angle < axis->min - 1e-9 || angle > axis->max + 1e-9) {
        report.errors.push_back(At(plan, planned.line) + "position " + std::to_string(i) + ": " +
                                name + " = " + Deg(angle) + " is outside the axis limits [" +
                                Deg(axis->min) + ", " + Deg(axis->max) + "]");
        check.reachable = false;
      }
    }
    if (check.reachable) {
      for (const auto& [name, angle] : planned.axes) {
        const double move = EstimateMoveS(angle - previous[name], timing);
        // Independent axes move at once when the plan allows it.
        check.move_s = plan.parallel_moves ? std::max(check.move_s, move) : check.move_s + move;
        previous[name] = angle;
      }
      CheckHighlight(g, planned.axes, &check);
      // A designed plan places some positions off the specular direction on purpose.
      if (!check.highlight_visible && !plan.design) {
        report.warnings.push_back(At(plan, planned.line) + "position " + std::to_string(i) +
                                  ": the highlight is not on the cut-out in the image (mirror "
                                  "point at x = " +
                                  std::to_string(check.highlight_x) +
                                  " m, y = " + std::to_string(check.highlight_y) + " m)");
      }
    }
    report.moves_s += check.move_s;
    report.settle_s += plan.settle_s;
    if (plan.auto_bracket) {
      report.exposures_s += plan.auto_settings.metering_s + timing.metering_s;
      // Unknown until metered: assume the metering exposure for every shot.
      report.exposures_s += shots * (plan.auto_settings.metering_s + timing.shot_overhead_s);
    } else {
      for (const double e : plan.exposures_s) report.exposures_s += e + timing.shot_overhead_s;
    }
    report.downloads_s += shots * timing.download_s;
    report.positions.push_back(check);
  }
  if (report.ok()) {
    std::vector<geometry::AxisPositions> axes;
    std::vector<bool> validation;
    for (const PlannedPosition& p : plan.positions) {
      axes.push_back(p.axes);
      validation.push_back(p.validation);
    }
    report.coverage = coverage::ComputeCoverage(g, axes, validation);
    report.has_coverage = true;
  }
  return report;
}

std::string PlanCheckReport::ToString() const {
  std::ostringstream out;
  out << "position  line  reachable  highlight  pixel (u, v)      theta_in  theta_max  move\n";
  char row[160];
  for (const PositionCheck& c : positions) {
    std::snprintf(
        row, sizeof row, "%8d  %4d  %-9s  %-9s  (%6.0f, %6.0f)  %7.1f°  %8.1f°  %5.1f s\n", c.index,
        c.line, c.reachable ? "yes" : "NO", c.highlight_visible ? "visible" : "NOT SEEN",
        c.highlight_u, c.highlight_v, Degrees(c.theta_in), Degrees(c.theta_max), c.move_s);
    out << row;
  }
  std::snprintf(row, sizeof row,
                "estimated duration %.1f s (moves %.1f s, settle %.1f s, exposures %.1f s, "
                "downloads %.1f s)\n",
                EstimatedDurationS(), moves_s, settle_s, exposures_s, downloads_s);
  out << row;
  if (has_coverage) out << coverage.ToString();
  if (!design.empty()) out << design;
  for (const std::string& e : errors) out << "error: " << e << "\n";
  for (const std::string& w : warnings) out << "warning: " << w << "\n";
  out << (ok() ? "plan OK" : "plan has errors") << "\n";
  return out.str();
}

std::string PlanCheckReport::ToJson() const {
  nlohmann::json j;
  j["ok"] = ok();
  j["errors"] = errors;
  j["warnings"] = warnings;
  j["exposures_s"] = bracket_s;  // empty: auto-bracketing
  j["estimated_duration_s"] = EstimatedDurationS();
  nlohmann::json list = nlohmann::json::array();
  for (std::size_t i = 0; i < resolved.size(); ++i) {
    nlohmann::json p;
    nlohmann::json axes = nlohmann::json::object();
    for (const auto& [name, angle] : resolved[i].axes) axes[name] = Degrees(angle);
    p["axes_deg"] = axes;
    p["validation"] = resolved[i].validation;
    if (has_coverage && i < coverage.positions.size()) {
      const coverage::PositionCoverage& c = coverage.positions[i];
      p["observed"] = c.observed;
      p["theta_in_deg"] = Degrees(c.theta_in);
      p["theta_out_deg"] = Degrees(c.theta_out);
      p["theta_h_deg"] = {Degrees(c.theta_h_min), Degrees(c.theta_h_max)};
      p["theta_d_deg"] = {Degrees(c.theta_d_min), Degrees(c.theta_d_max)};
      p["cells"] = c.cells.size();
      p["shared_cells"] = c.shared_cells;
      p["theta_h_bins"] = c.theta_h_bins;
      p["shared_theta_h_bins"] = c.shared_theta_h_bins;
    }
    if (i < positions.size()) p["highlight_visible"] = positions[i].highlight_visible;
    list.push_back(p);
  }
  j["positions"] = list;
  if (has_coverage) {
    j["coverage"] = {
        {"theta_h_bins", coverage.grid.theta_h_bins},
        {"theta_d_bins", coverage.grid.theta_d_bins},
        {"theta_h_axis", "sqrt"},
        {"covered_fraction", coverage.covered_fraction},
        {"covered_fraction_with_validation", coverage.covered_fraction_with_validation},
        {"theta_h_fraction", coverage.theta_h_fraction},
        {"shared_cell_fraction", coverage.shared_cell_fraction},
        {"shared_theta_h_fraction", coverage.shared_theta_h_fraction},
        {"theta_d_fraction", coverage.theta_d_fraction}};
  }
  if (!design.empty()) j["design"] = design;
  return j.dump(2) + "\n";
}

}  // namespace brdfrig::acquire
