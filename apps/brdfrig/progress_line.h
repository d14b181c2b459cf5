// A one-line progress display on stderr for runs (capture in the foreground, `brdfrig
// status --follow`), rewritten in place on a terminal and one line per change otherwise.
#pragma once

#include <unistd.h>

#include <cstdio>
#include <string>

#include "acquire/run_engine.h"

namespace brdfrig::apps {

class ProgressLine {
 public:
  ProgressLine() : tty_(isatty(STDERR_FILENO) != 0) {}

  void Show(const acquire::RunProgress& p) {
    char text[256];
    std::snprintf(text, sizeof text,
                  "[%-9s] position %d/%d  frame %d/%d  recorded %d/%d  ETA %.0f s  "
                  "saturated %.2f%%",
                  acquire::RunStateName(p.state), p.position + 1, p.positions, p.frame + 1,
                  p.frames_per_position, p.frames_recorded, p.frames_total, p.eta_s,
                  100 * p.last_saturation);
    std::string line = text;
    if (p.state == acquire::RunState::kFault || p.state == acquire::RunState::kPaused) {
      line += "  " + p.message;
    }
    if (line == last_) return;
    last_ = line;
    std::fprintf(stderr, tty_ ? "\r\033[K%s" : "%s\n", line.c_str());
    std::fflush(stderr);
  }

  void Finish() {
    if (tty_ && !last_.empty()) std::fprintf(stderr, "\n");
  }

 private:
  bool tty_;
  std::string last_;
};

}  // namespace brdfrig::apps
