// Running another program (sbatch, squeue, a configured hand-off command) without a shell, so
// that no path or argument is ever split or interpreted.
#pragma once

#include <atomic>
#include <cstddef>
#include <string>
#include <vector>

namespace brdfrig {

struct ProcessOptions {
  // A process group of its own, with default signal dispositions and an empty signal mask
  // (whatever the caller blocks or ignores): it and everything it starts can be ended
  // together, and when it exits, what it left running in that group is ended (SIGTERM,
  // SIGKILL after grace_s) instead of being waited for through the output it still holds.
  bool own_group = false;
  // Ended the same way after this long (0: no limit) or once `*stop` becomes true.
  double timeout_s = 0;
  const std::atomic<bool>* stop = nullptr;
  double grace_s = 2.0;  // between SIGTERM and SIGKILL
  // Only the last this many bytes of each output are kept (0: all of it): a long-running
  // command's chatter must not grow a service that only logs its last line.
  std::size_t keep_bytes = 0;
};

struct ProcessResult {
  // The program's exit status; 128 + N when signal N ended it; 127 when it could not be
  // started (not found, not executable).
  int exit_status = 127;
  std::string out;                                                   // what it wrote to stdout
  std::string err;                                                   // what it wrote to stderr
  enum class Ended { kNo, kTimedOut, kStopped } ended = Ended::kNo;  // why it was ended
  int leftovers = 0;  // own_group: processes it left running, ended after it exited
  bool ok() const { return exit_status == 0; }
};

// Runs argv[0] (looked up in PATH when it has no '/') with the rest as arguments and waits.
// stdin is /dev/null. Throws brdfrig::Error only when argv is empty or no pipe can be made.
ProcessResult RunProcess(const std::vector<std::string>& argv, const ProcessOptions& options = {});

// The command as a person would type it in a shell, each argument quoted where needed.
std::string ShellQuoted(const std::vector<std::string>& argv);
std::string ShellQuote(const std::string& word);

}  // namespace brdfrig
