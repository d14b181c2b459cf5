#include "coverage/design_request.h"

#include "common/error.h"

namespace brdfrig::coverage {

DesignOptions ParseDesignRequest(const YamlNode& node) {
  if (!node.IsMap()) node.Fail("expected a mapping {count: N, validation: M, ...}");
  DesignOptions o;
  const auto integer = [&](const char* key, int* field, int lo, int hi) {
    if (auto v = node.Optional(key)) *field = static_cast<int>(v->InRange(v->AsInt(), lo, hi));
  };
  const auto real = [&](const char* key, double* field, double lo, double hi) {
    if (auto v = node.Optional(key)) *field = v->InRange(v->AsDouble(), lo, hi);
  };
  // The same bounds as DesignOptions::Validate, checked here so that the error names the key.
  if (auto v = node.Optional("objective")) {
    o.objective = v->AsString();
    if (o.objective != "prior" && o.objective != "coverage") {
      v->Fail("expected 'prior' or 'coverage'");
    }
  }
  integer("prior_components", &o.prior_components, 1, 64);
  integer("count", &o.count, 1, 24);
  integer("validation", &o.validation, 0, 24);
  real("step_deg", &o.step_deg, 1, 45);
  integer("max_candidates", &o.max_candidates, 100, 1000000);
  integer("refine_passes", &o.refine_passes, 0, 20);
  integer("theta_h_reach_bins", &o.theta_h_reach_bins, 0, 16);
  integer("theta_d_reach_bins", &o.theta_d_reach_bins, 0, 16);
  real("min_separation_deg", &o.min_separation_deg, 0, 90);
  real("max_view_deg", &o.max_view_deg, 10, 89);
  real("max_light_deg", &o.max_light_deg, 10, 89.9);
  real("image_margin_px", &o.image_margin_px, 0, 1000);
  real("peak_theta_h_deg", &o.peak_theta_h_deg, 0.1, 45);
  real("retro_theta_d_deg", &o.retro_theta_d_deg, 0, 45);
  real("grazing_theta_in_deg", &o.grazing_theta_in_deg, 30, 89);
  real("cell_weight", &o.cell_weight, 0, 1e6);
  real("theta_h_weight", &o.theta_h_weight, 0, 1e6);
  real("theta_d_weight", &o.theta_d_weight, 0, 1e6);
  real("requirement_weight", &o.requirement_weight, 0, 1e6);
  node.Finish();
  try {
    o.Validate();
  } catch (const OptionsError& e) {
    node.Fail(e.what());
  }
  return o;
}

}  // namespace brdfrig::coverage
