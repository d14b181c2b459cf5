// A design request as written in plan.yaml or a scene's capture section:
//
//   positions: {design: {count: 6, validation: 1}}
//
// Every DesignOptions field can be given by its name (objective: prior or coverage,
// prior_components, count, validation, step_deg,
// max_candidates, refine_passes, theta_h_reach_bins, theta_d_reach_bins, min_separation_deg,
// max_view_deg, max_light_deg, image_margin_px, peak_theta_h_deg, retro_theta_d_deg,
// grazing_theta_in_deg, cell_weight, theta_h_weight, theta_d_weight, requirement_weight). count ≤
// 24 and max_candidates ≤ 10⁶ bound the search. Errors are FileErrors at the offending key
// (file:line:column).
#pragma once

#include "common/yaml_reader.h"
#include "coverage/designer.h"

namespace brdfrig::coverage {

DesignOptions ParseDesignRequest(const YamlNode& node);

}  // namespace brdfrig::coverage
