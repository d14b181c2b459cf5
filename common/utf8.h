// UTF-8 validity of text that goes into JSON (nlohmann::json refuses to serialize anything
// else, with an internal-looking message and no location).
#pragma once

#include <string>
#include <string_view>

namespace brdfrig {

// Throws FileError(source, line, column, ...) at the first byte that does not start or continue
// a well-formed UTF-8 sequence (RFC 3629: no overlongs, no surrogates, at most U+10FFFF).
// `source` names the text for the user: a file path, or e.g. "plan".
void RequireUtf8(std::string_view text, const std::string& source);

}  // namespace brdfrig
