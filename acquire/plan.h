// plan.yaml: what one capture session does. Angles in the file are degrees (like every
// human-written file of the project); in code they are radians.
//
//   sample: red-paint-01            # required
//   operator: alice                 # optional
//   notes: "second coat"            # optional
//   positions:                      # a list of axis angles (degrees) per position ...
//     - {camera_arm: 15, light_arm: -15}
//     - {camera_arm: 35, light_arm: -35}
//   # ... or a preset: camera_axis = θ and light_axis = −θ for `count` θ in [from, to]
//   # positions: {symmetric_arms: {from_deg: 20, to_deg: 60, count: 5,
//   #                              camera_axis: camera_arm, light_axis: light_arm}}
//   # ... or a plan designed for the rig by (θh, θd) coverage (coverage/designer.h):
//   # positions: {design: {count: 6, validation: 1}}
//   # An explicit position can be a validation position (captured, never fitted):
//   #   - {camera_arm: 30, light_arm: -10, validation: true}
//   exposures: [0.001, 0.008, 0.0666667]   # seconds, the bracket of every position, or
//   # exposures: {auto: {count: 3, metering_s: 0.008, highlight_max: 0.8, paper_level: 0.4}}
//   settle_s: 0.2                   # wait after a move before the first shot (default 0.2)
//   parallel_moves: true            # move independent axes at once (default true)
//
// Every error is a FileError naming file:line:column. Sizes are bounded (a plan is also what a
// daemon client sends): at most kMaxPlanPositions positions (listed or from symmetric_arms;
// a design has its own bound, 24) and kMaxBracketSize exposures per bracket.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "common/yaml_reader.h"
#include "coverage/designer.h"
#include "geometry/rig_geometry.h"

namespace brdfrig::acquire {

// A session of 1000 positions is many hours of rig time; a larger count is a typo (or an
// attack on the daemon: 2e9 positions would allocate gigabytes before any check).
inline constexpr int kMaxPlanPositions = 1000;
inline constexpr int kMaxBracketSize = 9;

struct PlannedPosition {
  geometry::AxisPositions axes;  // radians
  int line = 0;                  // where the position is written in the plan (1-based)
  bool validation = false;       // captured like the rest, left out of the fit
};

// Auto-bracketing: a metering shot at each position decides the bracket so that the highlight
// is below `highlight_max` (fraction of full scale) in the shortest exposure, and in the
// longest the paper reaches `paper_level` and the sample (the median of the cut-out's levels)
// `sample_level`, up to `longest_max_s`. The sample's level is ten times the reconstruction's
// noise floor (0.1 % of full scale): a dark sample then reads above it instead of being left
// out as noise. The median, not a low percentile: a glossy sample's darker part is its lobe's
// far tail, which no exposure a lab would wait for lifts above the floor.
struct AutoBracket {
  int count = 3;
  double metering_s = 0.008;
  double highlight_max = 0.8;
  double paper_level = 0.4;
  double sample_level = 0.01;
  double longest_max_s = 30;
};

struct Plan {
  std::string file;  // name used in messages (a path, or "submitted plan 'x'")
  std::string text;  // the plan exactly as written, stored in the session
  std::string sample;
  std::string operator_name;
  std::string notes;
  // Empty until ResolvePlan when the plan asks for a design (the rig decides the positions).
  std::vector<PlannedPosition> positions;
  std::optional<coverage::DesignOptions> design;
  int design_line = 0;
  std::vector<double> exposures_s;  // explicit bracket (seconds); empty when auto
  bool auto_bracket = false;
  AutoBracket auto_settings;
  double settle_s = 0.2;
  bool parallel_moves = true;
  int exposures_line = 0;

  // Shots per position.
  int BracketSize() const {
    return auto_bracket ? auto_settings.count : static_cast<int>(exposures_s.size());
  }
};

// Throws FileError (file:line:column) for anything malformed or unknown.
Plan ParsePlan(const YamlNode& root, const std::string& text);
Plan LoadPlanFile(const std::filesystem::path& path);
Plan LoadPlanString(const std::string& text, const std::string& source_name);

// Fills the positions of a designed plan for this rig (deterministic: the same plan and rig
// give the same positions, so a resumed session continues the same plan); returns the design
// (nullopt for an explicit plan, which is left as it is). Throws brdfrig::Error when the rig
// cannot satisfy the request.
std::optional<coverage::PlanDesign> ResolvePlan(Plan* plan, const geometry::RigGeometry& rig);

}  // namespace brdfrig::acquire
