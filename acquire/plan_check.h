// The dry run of a plan against a rig (`brdfrig plan check`): no device is opened. Checks
// that every axis exists and every angle is within the axis limits, estimates how long the
// session will take, and uses the nominal geometry to tell whether the specular highlight
// falls on the cut-out (inside the image) at each position, and which part of the (θh, θd)
// domain each position observes (coverage/coverage.h). A designed plan is resolved for the rig
// first, and the design's explanation is part of the report.
#pragma once

#include <string>
#include <vector>

#include "acquire/plan.h"
#include "common/angles.h"
#include "coverage/coverage.h"
#include "rig/rig_file.h"

namespace brdfrig::acquire {

// Device timings assumed by the estimate (a real rig's drives and camera are not asked).
struct TimingAssumptions {
  double axis_speed = Radians(20);         // rad/s
  double axis_acceleration = Radians(40);  // rad/s²
  double shot_overhead_s = 0.3;            // shutter lag etc. beyond the exposure
  double download_s = 1.2;                 // per frame
  double metering_s = 0.5;                 // an auto-bracketing metering shot, without download
};

struct PositionCheck {
  int index = 0;
  int line = 0;           // in the plan file
  bool reachable = true;  // every axis exists and is within its limits
  bool highlight_visible = false;
  double highlight_x = 0, highlight_y = 0;  // mirror point on the sample plane (metres)
  double highlight_u = 0, highlight_v = 0;  // ... and its pixel, when it projects
  double theta_in = 0;                      // incidence angle at the mirror point (radians)
  double theta_max = 0;  // largest angle from the mirror direction over the cut-out
  double move_s = 0;     // estimated move from the previous position
};

struct PlanCheckReport {
  std::vector<PositionCheck> positions;
  std::vector<PlannedPosition> resolved;  // the positions checked (a design's, once resolved)
  std::vector<double> bracket_s;          // the plan's explicit bracket (empty: auto)
  coverage::CoverageMap coverage;         // computed when every position is reachable
  bool has_coverage = false;
  std::string design;                 // the designer's explanation, for a designed plan
  std::vector<std::string> errors;    // each "file:line:column: ..." — the plan cannot run
  std::vector<std::string> warnings;  // runs, but the data may be poor (highlight not seen)
  double moves_s = 0, exposures_s = 0, downloads_s = 0, settle_s = 0;
  double EstimatedDurationS() const { return moves_s + exposures_s + downloads_s + settle_s; }
  bool ok() const { return errors.empty(); }
  std::string ToString() const;  // a table, the coverage, the design, errors and warnings
  // Resolved positions (axis values in degrees, role), exposures, coverage figures and the
  // duration estimate, for scripts (`brdfrig plan check --json`).
  std::string ToJson() const;
};

// Estimated time of one axis move (trapezoidal velocity profile).
double EstimateMoveS(double distance, const TimingAssumptions& timing);

PlanCheckReport CheckPlan(const Plan& plan, const geometry::RigDescription& rig,
                          const TimingAssumptions& timing = {});

}  // namespace brdfrig::acquire
