// UTC timestamps as the calibration files and rig.yaml write them (ISO 8601).
#pragma once

#include <ctime>
#include <optional>
#include <string>

namespace brdfrig {

// Now, as "2026-12-02T10:00:00Z".
std::string NowUtcIso8601();

// "2026-12-02T10:00:00Z" or a date alone ("2026-12-02", its midnight UTC) as seconds since
// the epoch; nullopt for anything else (other offsets, missing fields, impossible dates).
std::optional<std::time_t> ParseUtcIso8601(const std::string& text);

}  // namespace brdfrig
