// Running another program (sbatch, squeue, a configured hand-off command) without a shell, so
// that no path or argument is ever split or interpreted.
#pragma once

#include <string>
#include <vector>

namespace brdfrig {

struct ProcessResult {
  // The program's exit status; 128 + N when signal N ended it; 127 when it could not be
  // started (not found, not executable).
  int exit_status = 127;
  std::string out;  // what it wrote to stdout
  std::string err;  // what it wrote to stderr
  bool ok() const { return exit_status == 0; }
};

// Runs argv[0] (looked up in PATH when it has no '/') with the rest as arguments and waits.
// stdin is /dev/null. Throws brdfrig::Error only when argv is empty or no pipe can be made.
ProcessResult RunProcess(const std::vector<std::string>& argv);

// The command as a person would type it in a shell, each argument quoted where needed.
std::string ShellQuoted(const std::vector<std::string>& argv);
std::string ShellQuote(const std::string& word);

}  // namespace brdfrig
