#include "common/json_parse.h"

#include "common/error.h"

namespace brdfrig {

nlohmann::json ParseJson(std::string_view text, const std::string& source) {
  // Brackets inside strings do not count; in text that is not JSON the count may be off, and
  // the parser below says what is wrong.
  int depth = 0;
  bool in_string = false, escaped = false;
  for (const char c : text) {
    if (in_string) {
      if (escaped) {
        escaped = false;
      } else if (c == '\\') {
        escaped = true;
      } else if (c == '"') {
        in_string = false;
      }
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonDepth) {
        throw FileError(source, "arrays and objects nested more than " +
                                    std::to_string(kMaxJsonDepth) + " deep");
      }
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {  // syntax, or a number out of range (1e400)
    throw FileError(source, std::string("not valid JSON (") + e.what() + ")");
  }
}

}  // namespace brdfrig
