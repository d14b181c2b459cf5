// Text from the user's file system (capture names, paths, error messages quoting them) shown on
// one terminal line. A name may hold any byte but '/' and NUL: one with a newline must not split
// a report line into two that a script reads as two items.
#pragma once

#include <string>

namespace brdfrig {

// A path as it is when it holds no control character; otherwise as bash's $'...' quoting, which
// a user can paste back into a shell.
std::string DisplayPath(const std::string& path);

// A message (which may quote such a path) with its control characters escaped (\n, \xNN).
std::string OneLine(const std::string& text);

}  // namespace brdfrig
