// Runs the real `brdfrig` executable (path in BRDFRIG_BINARY, set by the test's CMake) with
// arguments, for tests of the command line: exit status and everything it printed.
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace brdfrig::testing {

struct CommandResult {
  int status = -1;     // exit status; -1 when killed by a signal
  std::string output;  // stdout and stderr together
};

inline CommandResult RunBrdfrig(const std::string& arguments) {
  CommandResult result;
  const std::string command = std::string(BRDFRIG_BINARY) + " " + arguments + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return result;
  std::array<char, 512> buffer;
  while (fgets(buffer.data(), buffer.size(), pipe) != nullptr) result.output += buffer.data();
  const int status = pclose(pipe);
  result.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

}  // namespace brdfrig::testing
