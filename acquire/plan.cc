#include "acquire/plan.h"

#include <cmath>

#include "common/angles.h"
#include "common/atomic_file.h"
#include "coverage/design_request.h"

namespace brdfrig::acquire {
namespace {

std::vector<PlannedPosition> ParseExplicitPositions(const YamlNode& list) {
  std::vector<PlannedPosition> positions;
  const std::vector<YamlNode> items = list.Elements();
  if (items.size() > static_cast<std::size_t>(kMaxPlanPositions)) {
    list.Fail(std::to_string(items.size()) + " positions: at most " +
              std::to_string(kMaxPlanPositions) + " per plan");
  }
  for (const YamlNode& item : items) {
    if (!item.IsMap()) item.Fail("expected a mapping from axis name to degrees");
    PlannedPosition position;
    position.line = item.line();
    for (const std::string& axis : item.Keys()) {
      if (axis == "validation") {
        position.validation = item.Required(axis).AsBool();
        continue;
      }
      position.axes[axis] = Radians(item.Required(axis).AsDouble());
    }
    if (position.axes.empty()) item.Fail("a position needs at least one axis angle");
    positions.push_back(std::move(position));
  }
  return positions;
}

std::vector<PlannedPosition> ParseSymmetricArms(const YamlNode& preset) {
  const double from = preset.Required("from_deg").AsDouble();
  const double to = preset.Required("to_deg").AsDouble();
  const YamlNode count_node = preset.Required("count");
  const int count = count_node.AsInt();
  if (count < 1 || count > kMaxPlanPositions) {
    count_node.Fail("count must be between 1 and " + std::to_string(kMaxPlanPositions) + ", got " +
                    std::to_string(count));
  }
  if (count == 1 && from != to) count_node.Fail("count 1 needs from_deg == to_deg");
  const std::string camera = preset.Get("camera_axis", "camera_arm");
  const std::string light = preset.Get("light_axis", "light_arm");
  preset.Finish();
  if (camera == light) preset.Fail("camera_axis and light_axis must differ");
  std::vector<PlannedPosition> positions;
  for (int i = 0; i < count; ++i) {
    const double theta = count == 1 ? from : from + (to - from) * i / (count - 1);
    PlannedPosition position;
    position.line = preset.line();
    // Camera at θ on one side of the normal, light at θ on the other: the mirror
    // configuration, so the highlight sits at the sample centre.
    position.axes[camera] = Radians(theta);
    position.axes[light] = -Radians(theta);
    positions.push_back(std::move(position));
  }
  return positions;
}

void ParseExposures(const YamlNode& node, Plan* plan) {
  plan->exposures_line = node.line();
  if (node.IsSequence()) {
    const std::vector<YamlNode> items = node.Elements();
    if (items.size() > static_cast<std::size_t>(kMaxBracketSize)) {
      node.Fail(std::to_string(items.size()) + " exposures: a bracket has at most " +
                std::to_string(kMaxBracketSize));
    }
    for (const YamlNode& item : items) {
      plan->exposures_s.push_back(item.Positive(item.AsDouble()));
    }
    if (plan->exposures_s.empty()) node.Fail("the bracket needs at least one exposure");
    return;
  }
  if (!node.IsMap()) node.Fail("expected a list of exposure times (s) or {auto: {...}}");
  const YamlNode settings = node.Required("auto");
  node.Finish();
  plan->auto_bracket = true;
  AutoBracket& a = plan->auto_settings;
  if (!settings.IsMap()) settings.Fail("expected a mapping (count, metering_s, ...)");
  if (auto count = settings.Optional("count")) {
    a.count = count->AsInt();
    if (a.count < 1 || a.count > kMaxBracketSize) {
      count->Fail("count must be between 1 and " + std::to_string(kMaxBracketSize));
    }
  }
  if (auto m = settings.Optional("metering_s")) a.metering_s = m->Positive(m->AsDouble());
  if (auto h = settings.Optional("highlight_max"))
    a.highlight_max = h->InRange(h->AsDouble(), 0.05, 1);
  if (auto p = settings.Optional("paper_level")) a.paper_level = p->InRange(p->AsDouble(), 0.01, 1);
  if (auto l = settings.Optional("sample_level"))
    a.sample_level = l->InRange(l->AsDouble(), 0.001, 1);
  if (auto l = settings.Optional("longest_max_s")) a.longest_max_s = l->Positive(l->AsDouble());
  if (a.longest_max_s < a.metering_s) {
    settings.Fail("longest_max_s (" + std::to_string(a.longest_max_s) +
                  " s) is shorter than metering_s (" + std::to_string(a.metering_s) + " s)");
  }
  settings.Finish();
}

}  // namespace

Plan ParsePlan(const YamlNode& root, const std::string& text) {
  if (!root.IsMap()) root.Fail("a plan is a mapping (sample, positions, exposures, ...)");
  Plan plan;
  plan.file = root.file();
  plan.text = text;
  plan.sample = root.Required("sample").AsString();
  if (plan.sample.empty()) root.Required("sample").Fail("the sample name must not be empty");
  plan.operator_name = root.Get("operator", "");
  plan.notes = root.Get("notes", "");
  const YamlNode positions = root.Required("positions");
  if (positions.IsSequence()) {
    plan.positions = ParseExplicitPositions(positions);
  } else if (positions.IsMap() && positions.Has("design")) {
    const YamlNode design = positions.Required("design");
    plan.design = coverage::ParseDesignRequest(design);
    plan.design_line = design.line();
    positions.Finish();
  } else if (positions.IsMap()) {
    plan.positions = ParseSymmetricArms(positions.Required("symmetric_arms"));
    positions.Finish();
  } else {
    positions.Fail("expected a list of positions, {symmetric_arms: {...}} or {design: {...}}");
  }
  if (plan.positions.empty() && !plan.design) positions.Fail("the plan has no position");
  if (auto exposures = root.Optional("exposures")) {
    ParseExposures(*exposures, &plan);
  } else {
    plan.auto_bracket = true;  // three exposures by default, decided by metering
    plan.exposures_line = root.line();
  }
  if (auto settle = root.Optional("settle_s")) {
    plan.settle_s = settle->InRange(settle->AsDouble(), 0, 60);
  }
  plan.parallel_moves = root.Get("parallel_moves", true);
  root.Finish();
  return plan;
}

Plan LoadPlanFile(const std::filesystem::path& path) {
  const std::string text = ReadFileToString(path);
  return ParsePlan(LoadYamlString(text, path.string()), text);
}

Plan LoadPlanString(const std::string& text, const std::string& source_name) {
  return ParsePlan(LoadYamlString(text, source_name), text);
}

std::optional<coverage::PlanDesign> ResolvePlan(Plan* plan, const geometry::RigGeometry& rig) {
  if (!plan->design) return std::nullopt;
  coverage::PlanDesign design;
  try {
    design = coverage::DesignPlan(rig, *plan->design);
  } catch (const Error& e) {
    throw Error(plan->file + ":" + std::to_string(plan->design_line) + ": " + e.what());
  }
  plan->positions.clear();
  for (const coverage::DesignedPosition& d : design.positions) {
    PlannedPosition position;
    position.axes = d.coverage.axes;
    position.line = plan->design_line;
    position.validation = d.coverage.validation;
    plan->positions.push_back(std::move(position));
  }
  return design;
}

}  // namespace brdfrig::acquire
