// `brdfrig rig simcamera` as a child process for the tests of the real binary under bad
// clients: an optional descriptor limit (the lab's `ulimit -n`), the port it prints, its CPU
// time and open descriptors from /proc, and Ctrl-C with a deadline, so that a camera that
// cannot be stopped fails the test instead of hanging it.
#pragma once

#include <dirent.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "tests/common/run_brdfrig.h"

namespace brdfrig::simcamera::testing {

class CameraProcess {
 public:
  // Starts BRDFRIG_BINARY with `args`; `max_descriptors` > 0 sets RLIMIT_NOFILE in the child.
  CameraProcess(std::vector<std::string> args, int max_descriptors = 0) {
    pid_ = brdfrig::testing::SpawnBrdfrig(std::move(args), &output_, max_descriptors);
    if (output_ == nullptr) return;
    // The first line names the port ("... serving on ptpip:127.0.0.1:PORT:PORT (scene ...").
    char line[1024];
    while (port_ == 0 && fgets(line, sizeof line, output_) != nullptr) {
      const std::string text = line;
      first_lines_ += text;
      const auto at = text.find("ptpip:127.0.0.1:");
      if (at != std::string::npos) port_ = std::atoi(text.c_str() + at + 16);
    }
  }
  ~CameraProcess() {
    if (pid_ > 0) {
      kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
    }
    if (output_ != nullptr) fclose(output_);
  }
  CameraProcess(const CameraProcess&) = delete;
  CameraProcess& operator=(const CameraProcess&) = delete;

  int port() const { return port_; }
  const std::string& first_lines() const { return first_lines_; }

  // User and system CPU seconds so far.
  double cpu_seconds() const {
    std::ifstream in("/proc/" + std::to_string(pid_) + "/stat");
    std::string stat((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::istringstream fields(stat.substr(stat.rfind(')') + 2));
    std::string field;
    double ticks = 0;
    for (int i = 3; i <= 15 && fields >> field; ++i) {
      if (i == 14 || i == 15) ticks += std::stod(field);  // utime, stime
    }
    return ticks / static_cast<double>(sysconf(_SC_CLK_TCK));
  }

  int open_descriptors() const {
    int count = 0;
    if (DIR* dir = opendir(("/proc/" + std::to_string(pid_) + "/fd").c_str())) {
      while (readdir(dir) != nullptr) ++count;
      closedir(dir);
    }
    return count - 2;
  }

  struct Stopped {
    bool exited = false;  // within the deadline
    int status = -1;
    std::string output;
  };
  // Ctrl-C; waits at most `limit` for the exit, then kills it (exited = false).
  Stopped Stop(std::chrono::milliseconds limit) {
    Stopped result;
    kill(pid_, SIGINT);
    const auto end = std::chrono::steady_clock::now() + limit;
    int status = 0;
    while (waitpid(pid_, &status, WNOHANG) == 0) {
      if (std::chrono::steady_clock::now() > end) {
        kill(pid_, SIGKILL);
        waitpid(pid_, &status, 0);
        pid_ = -1;
        return result;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    pid_ = -1;
    result.exited = true;
    result.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    char line[1024];
    while (fgets(line, sizeof line, output_) != nullptr) result.output += line;
    return result;
  }

 private:
  pid_t pid_ = -1;
  int port_ = 0;
  std::string first_lines_;
  FILE* output_ = nullptr;
};

}  // namespace brdfrig::simcamera::testing
