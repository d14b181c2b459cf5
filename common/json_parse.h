// The one way JSON text is parsed (material files, manifests, task results, catalog cells,
// daemon requests): nesting deeper than kMaxJsonDepth is refused before nlohmann::json builds
// a document, since copying, printing or comparing one recurses once per level (a file nested
// 200,000 arrays deep overflowed the stack).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

namespace brdfrig {

// Far above any file brdfrig writes (a material is 4 deep), far below the stack's limit.
inline constexpr int kMaxJsonDepth = 64;

// Throws FileError naming `source` (a file, or e.g. "request body") when `text` is nested more
// than kMaxJsonDepth arrays and objects deep or is not valid JSON.
nlohmann::json ParseJson(std::string_view text, const std::string& source);

}  // namespace brdfrig
