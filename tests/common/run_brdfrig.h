// Runs the real `brdfrig` executable (path in BRDFRIG_BINARY, set by the test's CMake) with
// arguments, for tests of the command line: exit status and everything it printed.
#pragma once

#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

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

// Starts `brdfrig ARGS...` with its stdout on a pipe the returned FILE reads (stderr stays the
// test's); `max_descriptors` > 0 sets RLIMIT_NOFILE in the child (the lab's `ulimit -n`).
// Returns the child's pid, or -1 (and no FILE) when it could not be started.
inline pid_t SpawnBrdfrig(std::vector<std::string> args, FILE** output, int max_descriptors = 0) {
  *output = nullptr;
  args.insert(args.begin(), BRDFRIG_BINARY);
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  int out[2];
  if (pipe(out) != 0) return -1;
  const pid_t pid = fork();
  if (pid == 0) {
    dup2(out[1], STDOUT_FILENO);
    close(out[0]);
    close(out[1]);
    if (max_descriptors > 0) {
      const rlimit limit{static_cast<rlim_t>(max_descriptors),
                         static_cast<rlim_t>(max_descriptors)};
      setrlimit(RLIMIT_NOFILE, &limit);
    }
    execv(BRDFRIG_BINARY, argv.data());
    _exit(127);
  }
  close(out[1]);
  if (pid < 0) {
    close(out[0]);
    return -1;
  }
  *output = fdopen(out[0], "r");
  return pid;
}

// `brdfrig ARGS...` in the background until Stop() (Ctrl-C); keeps the first line it prints,
// which names where it serves (the simulated drive and camera print their port first).
class BackgroundBrdfrig {
 public:
  explicit BackgroundBrdfrig(std::vector<std::string> args) {
    pid_ = SpawnBrdfrig(std::move(args), &output_);
    if (output_ == nullptr) return;
    char line[512];
    if (fgets(line, sizeof(line), output_) != nullptr) first_line_ = line;
  }
  BackgroundBrdfrig(const BackgroundBrdfrig&) = delete;
  BackgroundBrdfrig& operator=(const BackgroundBrdfrig&) = delete;
  // Sends Ctrl-C and returns the exit status and the rest of the output.
  CommandResult Stop() {
    CommandResult result;
    kill(pid_, SIGINT);
    char line[512];
    while (fgets(line, sizeof(line), output_) != nullptr) result.output += line;
    int status = 0;
    waitpid(pid_, &status, 0);
    pid_ = -1;
    result.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return result;
  }
  ~BackgroundBrdfrig() {
    if (pid_ > 0) Stop();
    if (output_ != nullptr) fclose(output_);
  }
  const std::string& first_line() const { return first_line_; }
  // The number after the last ':' of the first line ("... serving on tcp://127.0.0.1:PORT").
  int port() const {
    const auto colon = first_line_.rfind(':');
    return colon == std::string::npos ? 0 : std::atoi(first_line_.c_str() + colon + 1);
  }

 private:
  pid_t pid_ = -1;
  FILE* output_ = nullptr;
  std::string first_line_;
};

}  // namespace brdfrig::testing
