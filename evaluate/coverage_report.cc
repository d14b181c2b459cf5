#include "evaluate/coverage_report.h"

#include "common/angles.h"
#include "common/error.h"
#include "common/format.h"

namespace brdfrig::evaluate {
namespace {

using nlohmann::json;

json RangeDeg(double lo, double hi) { return json::array({Degrees(lo), Degrees(hi)}); }

std::string Percent(double fraction) { return Fixed(100 * fraction, 1) + " %"; }

}  // namespace

json CoverageJson(const coverage::CoverageMap& map, const std::string& plan) {
  json out = {{"plan", plan},
              {"method",
               "(θh, θd) of 41 × 41 points over the cut-out from the rig's nominal camera and "
               "light at each position (no photos), cells of a grid over [0°, 90°]² with a "
               "sqrt-warped θh axis (coverage/coverage.h)"},
              {"grid",
               {{"theta_h_bins", map.grid.theta_h_bins},
                {"theta_d_bins", map.grid.theta_d_bins},
                {"samples_per_side", map.grid.samples_per_side}}},
              {"covered_fraction", map.covered_fraction},
              {"covered_fraction_with_validation", map.covered_fraction_with_validation},
              {"theta_h_fraction", map.theta_h_fraction},
              {"theta_d_fraction", map.theta_d_fraction},
              {"shared_cell_fraction", map.shared_cell_fraction},
              {"shared_theta_h_fraction", map.shared_theta_h_fraction},
              {"positions", json::array()}};
  for (std::size_t i = 0; i < map.positions.size(); ++i) {
    const coverage::PositionCoverage& p = map.positions[i];
    json axes = json::object();
    for (const auto& [name, angle] : p.axes) axes[name] = Degrees(angle);
    json j = {
        {"index", i}, {"validation", p.validation}, {"observed", p.observed}, {"axes_deg", axes}};
    if (!p.observed) {
      j["problem"] = p.problem;
    } else {
      j["theta_in_deg"] = Degrees(p.theta_in);
      j["theta_out_deg"] = Degrees(p.theta_out);
      j["theta_h_deg"] = RangeDeg(p.theta_h_min, p.theta_h_max);
      j["theta_d_deg"] = RangeDeg(p.theta_d_min, p.theta_d_max);
      j["cell_count"] = p.cells.size();
      j["cells"] = p.cells;
      j["shared_cells"] = p.shared_cells;
    }
    out["positions"].push_back(j);
  }
  return out;
}

coverage::CoverageMap CoverageMapFromJson(const json& c) {
  try {
    coverage::CoverageMap map;
    const json& grid = c.at("grid");
    map.grid.theta_h_bins = grid.at("theta_h_bins").get<int>();
    map.grid.theta_d_bins = grid.at("theta_d_bins").get<int>();
    map.grid.samples_per_side = grid.at("samples_per_side").get<int>();
    map.covered_fraction = c.at("covered_fraction").get<double>();
    map.covered_fraction_with_validation = c.at("covered_fraction_with_validation").get<double>();
    map.theta_h_fraction = c.at("theta_h_fraction").get<double>();
    map.theta_d_fraction = c.at("theta_d_fraction").get<double>();
    map.shared_cell_fraction = c.at("shared_cell_fraction").get<double>();
    map.shared_theta_h_fraction = c.at("shared_theta_h_fraction").get<double>();
    const int cells = map.grid.theta_h_bins * map.grid.theta_d_bins;
    for (const json& j : c.at("positions")) {
      coverage::PositionCoverage p;
      p.validation = j.at("validation").get<bool>();
      p.observed = j.at("observed").get<bool>();
      for (const auto& [name, deg] : j.at("axes_deg").items())
        p.axes[name] = Radians(deg.get<double>());
      if (!p.observed) {
        p.problem = j.value("problem", "");
      } else {
        p.theta_in = Radians(j.at("theta_in_deg").get<double>());
        p.theta_out = Radians(j.at("theta_out_deg").get<double>());
        p.theta_h_min = Radians(j.at("theta_h_deg").at(0).get<double>());
        p.theta_h_max = Radians(j.at("theta_h_deg").at(1).get<double>());
        p.theta_d_min = Radians(j.at("theta_d_deg").at(0).get<double>());
        p.theta_d_max = Radians(j.at("theta_d_deg").at(1).get<double>());
        p.cells = j.at("cells").get<std::vector<int>>();
        p.shared_cells = j.at("shared_cells").get<int>();
        for (int cell : p.cells) {
          if (cell < 0 || cell >= cells) {
            throw Error("cell " + std::to_string(cell) + " outside the " + std::to_string(cells) +
                        "-cell grid");
          }
        }
      }
      map.positions.push_back(std::move(p));
    }
    return map;
  } catch (const json::exception& e) {
    throw Error(std::string("report.json: figures.coverage: ") + e.what());
  } catch (const Error& e) {
    throw Error(std::string("report.json: figures.coverage: ") + e.what());
  }
}

ReportSection CoverageSection(const json& c) {
  const coverage::CoverageMap map = CoverageMapFromJson(c);
  ReportSection s{"What the photos covered", {}, {}, {}, {}};
  s.paragraphs.push_back(
      "Where " + c.at("plan").get<std::string>() +
      " observes the material in (θh, θd), the half-vector and difference angles (an isotropic "
      "BRDF is mostly a function of these two): " +
      c.at("method").get<std::string>() + ".");
  s.paragraphs.push_back(
      "Covered by the fitted positions: " + Percent(map.covered_fraction) + " of the cells (" +
      Percent(map.covered_fraction_with_validation) + " with the validation positions); " +
      Percent(map.theta_h_fraction) + " of the θh bins and " + Percent(map.theta_d_fraction) +
      " of the θd bins (how much of a shared D(θh) and F(θd) the plan constrains); " +
      Percent(map.shared_cell_fraction) +
      " of the fitted positions' cells are seen by another "
      "fitted position.");
  s.svg_plots.push_back(coverage::CoverageSvg(map, "Coverage in (θh, θd)"));
  Table t{"Each position's (θh, θd) patch (nominal geometry, at the cut-out's centre and over it)",
          {"position", "role", "axes (deg)", "theta_in (deg)", "theta_out (deg)", "θh (deg)",
           "θd (deg)", "cells", "shared cells"},
          {}};
  for (const json& j : c.at("positions")) {
    std::string axes;
    for (const auto& [name, deg] : j.at("axes_deg").items()) {
      axes += (axes.empty() ? "" : " ") + name + "=" + Fixed(deg.get<double>(), 1);
    }
    const std::string role = j.at("validation").get<bool>() ? "validation" : "fit";
    const std::string index = std::to_string(j.at("index").get<int>());
    if (!j.at("observed").get<bool>()) {
      t.rows.push_back({index, role, axes, "not observed: " + j.value("problem", "")});
      continue;
    }
    auto range = [&](const char* key) {
      return Fixed(j.at(key).at(0).get<double>(), 1) + "–" +
             Fixed(j.at(key).at(1).get<double>(), 1);
    };
    t.rows.push_back({index, role, axes, Fixed(j.at("theta_in_deg").get<double>(), 1),
                      Fixed(j.at("theta_out_deg").get<double>(), 1), range("theta_h_deg"),
                      range("theta_d_deg"), std::to_string(j.at("cell_count").get<int>()),
                      std::to_string(j.at("shared_cells").get<int>())});
  }
  s.tables.push_back(t);
  return s;
}

}  // namespace brdfrig::evaluate
