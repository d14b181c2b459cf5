// Invariants of the code: BRDFRIG_CHECK(condition, note). A failed check is a bug in
// brdfrig, not a user, file or hardware error (those throw brdfrig::Error with a message a
// person can act on). It prints file:line, the condition and a note, then aborts; it stays on in
// every build type.
#pragma once

#include <cstdio>
#include <cstdlib>

namespace brdfrig::internal {

[[noreturn]] inline void CheckFailed(const char* file, int line, const char* condition,
                                     const char* note) {
  std::fprintf(stderr, "%s:%d: BRDFRIG_CHECK(%s) failed: %s (a bug in brdfrig)\n", file, line,
               condition, note);
  std::abort();
}

}  // namespace brdfrig::internal

// BRDFRIG_CHECK(condition, "what the caller got wrong")
#define BRDFRIG_CHECK(condition, note)                                                        \
  do {                                                                                        \
    if (!(condition)) ::brdfrig::internal::CheckFailed(__FILE__, __LINE__, #condition, note); \
  } while (false)
