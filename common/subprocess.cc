#include "common/subprocess.h"

#include <dirent.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <fstream>
#include <functional>
#include <sstream>

#include "common/error.h"

extern char** environ;

namespace brdfrig {
namespace {

using Clock = std::chrono::steady_clock;

// The program's stdout and stderr, read without blocking. Both ends close on exec: the child
// gets its copies through dup2 only, so no other program started meanwhile (another thread)
// holds a write end open.
class OutputPipes {
 public:
  explicit OutputPipes(std::size_t keep_bytes) : keep_(keep_bytes) {
    for (auto& fds : pipes_) {
      if (::pipe2(fds.data(), O_CLOEXEC) != 0) {
        Close();
        throw Error(std::string("cannot create a pipe: ") + std::strerror(errno));
      }
    }
  }
  ~OutputPipes() { Close(); }
  OutputPipes(const OutputPipes&) = delete;
  OutputPipes& operator=(const OutputPipes&) = delete;

  int write_end(int i) const { return pipes_[i][1]; }
  // After the spawn: the child holds its own copies of the write ends.
  void CloseWriteEnds() {
    for (auto& fds : pipes_) CloseFd(fds[1]);
    for (auto& fds : pipes_) ::fcntl(fds[0], F_SETFL, O_NONBLOCK);
  }
  bool open() const { return pipes_[0][0] >= 0 || pipes_[1][0] >= 0; }
  // Reads what is there, waiting at most `wait_ms` (-1: until something happens).
  void Read(int wait_ms) {
    std::array<pollfd, 2> fds{{{pipes_[0][0], POLLIN, 0}, {pipes_[1][0], POLLIN, 0}}};
    if (::poll(fds.data(), fds.size(), wait_ms) <= 0) return;
    for (std::size_t i = 0; i < fds.size(); ++i) {
      if (fds[i].fd < 0 || fds[i].revents == 0) continue;
      std::array<char, 4096> buffer;
      for (;;) {
        const ssize_t n = ::read(fds[i].fd, buffer.data(), buffer.size());
        if (n > 0) {
          text_[i].append(buffer.data(), static_cast<std::size_t>(n));
          if (keep_ > 0 && text_[i].size() > keep_) text_[i].erase(0, text_[i].size() - keep_);
          continue;
        }
        if (n < 0 && errno == EINTR) continue;
        if (n == 0 || errno != EAGAIN) CloseFd(pipes_[i][0]);  // end of file or error
        break;
      }
    }
  }
  std::string& out() { return text_[0]; }
  std::string& err() { return text_[1]; }
  void Close() {
    for (auto& fds : pipes_) {
      CloseFd(fds[0]);
      CloseFd(fds[1]);
    }
  }

 private:
  static void CloseFd(int& fd) {
    if (fd >= 0) ::close(fd);
    fd = -1;
  }
  std::size_t keep_ = 0;
  std::array<std::array<int, 2>, 2> pipes_{{{-1, -1}, {-1, -1}}};
  std::array<std::string, 2> text_;
};

// Whether the child has exited, without reaping it: while it is a zombie its pid (and so its
// process group's id) cannot be given to another process, so signals to -pid stay safe.
bool Exited(pid_t pid) {
  siginfo_t info{};
  if (::waitid(P_PID, static_cast<id_t>(pid), &info, WEXITED | WNOHANG | WNOWAIT) != 0) {
    return errno != EINTR;  // ECHILD: gone already; never loop on it
  }
  return info.si_pid == pid;
}

// Processes of `group` still running (zombies excluded), from /proc: a command's background
// children stay in its group unless they detach on purpose.
int LiveMembers(pid_t group) {
  int live = 0;
  DIR* proc = ::opendir("/proc");
  if (proc == nullptr) return 0;
  while (const dirent* entry = ::readdir(proc)) {
    const std::string pid = entry->d_name;
    if (pid.empty() || pid.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream stat_file("/proc/" + pid + "/stat");
    std::string line;
    if (!std::getline(stat_file, line)) continue;
    // "pid (comm) state ppid pgrp ...": comm may hold spaces and parentheses.
    const std::size_t close = line.rfind(')');
    if (close == std::string::npos) continue;
    std::istringstream fields(line.substr(close + 1));
    char state = 0;
    long parent = 0, pgrp = 0;
    if (!(fields >> state >> parent >> pgrp)) continue;
    live += pgrp == group && state != 'Z' && state != 'X';
  }
  ::closedir(proc);
  return live;
}

// Sends SIGTERM to `target` (a pid, or -group), then SIGKILL once `done` has not come true
// within `grace_s`, reading the output meanwhile so that nothing blocks on a full pipe.
void End(pid_t target, double grace_s, OutputPipes& pipes, const std::function<bool()>& done) {
  ::kill(target, SIGTERM);
  const auto kill_at = Clock::now() + std::chrono::duration<double>(grace_s);
  while (!done() && Clock::now() < kill_at) pipes.Read(10);
  if (!done()) ::kill(target, SIGKILL);
}

}  // namespace

ProcessResult RunProcess(const std::vector<std::string>& argv, const ProcessOptions& options) {
  if (argv.empty()) throw Error("RunProcess: no program given");
  OutputPipes pipes(options.keep_bytes);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, pipes.write_end(0), STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, pipes.write_end(1), STDERR_FILENO);
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  if (options.own_group) {
    posix_spawnattr_setpgroup(&attributes, 0);
    sigset_t none, defaults;
    sigemptyset(&none);
    sigemptyset(&defaults);
    for (int sig : {SIGPIPE, SIGTERM, SIGINT, SIGHUP, SIGQUIT}) sigaddset(&defaults, sig);
    posix_spawnattr_setsigmask(&attributes, &none);
    posix_spawnattr_setsigdefault(&attributes, &defaults);
    posix_spawnattr_setflags(
        &attributes, POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
  }
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = -1;
  const int spawned = ::posix_spawnp(&pid, args[0], &actions, &attributes, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attributes);
  pipes.CloseWriteEnds();
  ProcessResult result;
  if (spawned != 0) {
    result.err = argv[0] + ": " + std::strerror(spawned);
    return result;
  }
  const pid_t target = options.own_group ? -pid : pid;
  const auto deadline = options.timeout_s > 0
                            ? Clock::now() + std::chrono::duration<double>(options.timeout_s)
                            : Clock::time_point::max();
  bool exited = false;
  while (!(exited = Exited(pid))) {
    if (options.stop != nullptr && options.stop->load()) {
      result.ended = ProcessResult::Ended::kStopped;
      break;
    }
    if (Clock::now() >= deadline) {
      result.ended = ProcessResult::Ended::kTimedOut;
      break;
    }
    pipes.Read(50);
  }
  if (!exited) {
    End(target, options.grace_s, pipes, [pid] { return Exited(pid); });
    while (!Exited(pid)) pipes.Read(10);
  }
  pipes.Read(0);  // its last words
  if (options.own_group) {
    // Background children may hold the output pipes forever (`sleep infinity &`): the
    // program has exited, so what it left in its group is ended rather than waited for.
    result.leftovers = LiveMembers(pid);
    if (result.leftovers > 0) {
      End(-pid, options.grace_s, pipes, [pid] { return LiveMembers(pid) == 0; });
    }
  } else {
    while (pipes.open()) pipes.Read(-1);  // everything it wrote, as long as anyone writes
  }
  pipes.Close();
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  result.exit_status = WIFEXITED(status)     ? WEXITSTATUS(status)
                       : WIFSIGNALED(status) ? 128 + WTERMSIG(status)
                                             : 127;
  result.out = std::move(pipes.out());
  result.err = std::move(pipes.err());
  return result;
}

std::string ShellQuote(const std::string& word) {
  const bool plain = !word.empty() && word.find_first_not_of(
                                          "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                          "0123456789_-+=./:,%@") == std::string::npos;
  if (plain) return word;
  std::string quoted = "'";
  for (char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

std::string ShellQuoted(const std::vector<std::string>& argv) {
  std::string line;
  for (const std::string& a : argv) line += (line.empty() ? "" : " ") + ShellQuote(a);
  return line;
}

}  // namespace brdfrig
