// The plan's coverage of the (θh, θd) square (coverage/coverage.h: from the rig's nominal
// geometry, no photos) in a report: report.json holds the numbers — the covered fractions, and
// per position its (θh, θd) patch (ranges, incidence and view angles at the cut-out's centre,
// occupied cells) — and the HTML draws the map with coverage/'s own SVG, rebuilt from them.
// report.json: "figures": {"coverage": {...}}.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "coverage/coverage.h"
#include "evaluate/report.h"

namespace brdfrig::evaluate {

// `plan` names the plan in the report (e.g. "the capture plan of sim/scenes/default.yaml").
nlohmann::json CoverageJson(const coverage::CoverageMap& map, const std::string& plan);

// The map back from that json: grid, fractions, and per position its role, axes, angles and
// cells (what CoverageSvg draws). Throws brdfrig::Error for a malformed object.
coverage::CoverageMap CoverageMapFromJson(const nlohmann::json& coverage);

// The report's section: the fractions, the map, and a table of the positions' patches.
ReportSection CoverageSection(const nlohmann::json& coverage);

}  // namespace brdfrig::evaluate
