// The run progress as the daemon's control API carries it (`GET /status` → "progress"): both
// halves of the protocol, so that the daemon (encoding) and `brdfrig status|submit --follow`
// (decoding) cannot drift apart.
#pragma once

#include <nlohmann/json.hpp>

#include "acquire/run_engine.h"

namespace brdfrig::acquire {

nlohmann::json ProgressToJson(const RunProgress& progress);

// Missing fields take RunProgress's defaults; an unknown state reads as idle.
RunProgress ProgressFromJson(const nlohmann::json& json);

}  // namespace brdfrig::acquire
