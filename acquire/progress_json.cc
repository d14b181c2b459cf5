#include "acquire/progress_json.h"

#include <string>

namespace brdfrig::acquire {

using nlohmann::json;

json ProgressToJson(const RunProgress& p) {
  return json{{"state", RunStateName(p.state)},
              {"position", p.position},
              {"positions", p.positions},
              {"frame", p.frame},
              {"frames_per_position", p.frames_per_position},
              {"frames_recorded", p.frames_recorded},
              {"frames_total", p.frames_total},
              {"eta_s", p.eta_s},
              {"last_saturation", p.last_saturation},
              {"message", p.message}};
}

RunProgress ProgressFromJson(const json& p) {
  RunProgress progress;
  const std::string state = p.value("state", "idle");
  for (auto s : {RunState::kIdle, RunState::kMoving, RunState::kAcquiring, RunState::kPaused,
                 RunState::kFault, RunState::kDone}) {
    if (state == RunStateName(s)) progress.state = s;
  }
  progress.position = p.value("position", 0);
  progress.positions = p.value("positions", 0);
  progress.frame = p.value("frame", 0);
  progress.frames_per_position = p.value("frames_per_position", 0);
  progress.frames_recorded = p.value("frames_recorded", 0);
  progress.frames_total = p.value("frames_total", 0);
  progress.eta_s = p.value("eta_s", 0.0);
  progress.last_saturation = p.value("last_saturation", 0.0);
  progress.message = p.value("message", "");
  return progress;
}

}  // namespace brdfrig::acquire
