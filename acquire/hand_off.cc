#include "acquire/hand_off.h"

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
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <sstream>
#include <vector>

#include "common/error.h"
#include "common/subprocess.h"

extern char** environ;

namespace brdfrig::acquire {

namespace {

using Clock = std::chrono::steady_clock;

// One pass over the argument as written: a session directory that itself contains "{name}"
// (a data_dir of that name) stays the directory it is.
std::string Substitute(const std::string& argument, const std::string& session,
                       const std::string& name) {
  static const std::string kSession = "{session}", kName = "{name}";
  std::string out;
  for (std::size_t i = 0; i < argument.size();) {
    if (argument.compare(i, kSession.size(), kSession) == 0) {
      out += session;
      i += kSession.size();
    } else if (argument.compare(i, kName.size(), kName) == 0) {
      out += name;
      i += kName.size();
    } else {
      out += argument[i++];
    }
  }
  return out;
}

std::string LastLine(std::string text) {
  while (!text.empty() && text.back() == '\n') text.pop_back();
  const std::size_t newline = text.rfind('\n');
  return newline == std::string::npos ? text : text.substr(newline + 1);
}

std::string Seconds(double s) {
  std::ostringstream text;
  text << s << " s";
  return text.str();
}

// The command's stdout and stderr, read without blocking. Only the tail is kept: the log shows
// the last line, and a chatty command must not grow the daemon.
class OutputPipes {
 public:
  static constexpr std::size_t kKeep = 8192;

  OutputPipes() {
    for (auto& fds : pipes_) {
      if (::pipe2(fds.data(), O_CLOEXEC) != 0) {
        Close();
        throw Error(std::string("cannot create a pipe for the hand-off: ") + std::strerror(errno));
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
  // Reads what is there, waiting at most `wait_ms` for something to arrive.
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
          if (text_[i].size() > kKeep) text_[i].erase(0, text_[i].size() - kKeep);
          continue;
        }
        if (n < 0 && errno == EINTR) continue;
        if (n == 0 || errno != EAGAIN) CloseFd(pipes_[i][0]);  // end of file or error
        break;
      }
    }
  }
  const std::string& out() const { return text_[0]; }
  const std::string& err() const { return text_[1]; }
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

struct Outcome {
  int exit_status = 127;  // 128 + N when signal N ended it; 127 when it could not start
  std::string out, err;
  std::string ended;  // why the command itself was ended ("" when it exited on its own)
  int leftovers = 0;  // processes still running in its group after it exited, then ended
};

// Sends SIGTERM to the group, then SIGKILL once `done` has not come true within the grace.
void EndGroup(pid_t group, OutputPipes& pipes, const std::function<bool()>& done) {
  ::kill(-group, SIGTERM);
  const auto kill_at = Clock::now() + std::chrono::duration<double>(kHandOffGraceS);
  while (!done() && Clock::now() < kill_at) pipes.Read(10);
  if (!done()) ::kill(-group, SIGKILL);
}

Outcome RunInOwnGroup(const std::vector<std::string>& argv, double timeout_s,
                      const std::atomic<bool>* stop) {
  Outcome outcome;
  OutputPipes pipes;
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, pipes.write_end(0), STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, pipes.write_end(1), STDERR_FILENO);
  // Its own process group, so that it and whatever it starts can be ended together; the
  // daemon's blocked SIGTERM/SIGINT and ignored SIGPIPE are not the command's.
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  posix_spawnattr_setpgroup(&attributes, 0);
  sigset_t none, defaults;
  sigemptyset(&none);
  sigemptyset(&defaults);
  for (int sig : {SIGPIPE, SIGTERM, SIGINT, SIGHUP, SIGQUIT}) sigaddset(&defaults, sig);
  posix_spawnattr_setsigmask(&attributes, &none);
  posix_spawnattr_setsigdefault(&attributes, &defaults);
  posix_spawnattr_setflags(&attributes,
                           POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = -1;
  const int spawned = ::posix_spawn(&pid, args[0], &actions, &attributes, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attributes);
  pipes.CloseWriteEnds();
  if (spawned != 0) {
    outcome.err = argv[0] + ": " + std::strerror(spawned);
    return outcome;
  }
  const auto deadline = Clock::now() + std::chrono::duration<double>(timeout_s);
  bool exited = false;
  while (!(exited = Exited(pid))) {
    if (stop != nullptr && stop->load()) {
      outcome.ended = "was ended because the daemon is stopping";
      break;
    }
    if (Clock::now() >= deadline) {
      outcome.ended = "timed out after " + Seconds(timeout_s) + ", so it was ended";
      break;
    }
    pipes.Read(50);
  }
  if (!exited) {
    EndGroup(pid, pipes, [pid] { return Exited(pid); });
    while (!Exited(pid)) pipes.Read(10);
  }
  pipes.Read(0);  // its last words
  // Background children may hold the output pipes forever (`sleep infinity &`): the command
  // has exited, so what it left in its group is ended rather than waited for.
  outcome.leftovers = LiveMembers(pid);
  if (outcome.leftovers > 0) EndGroup(pid, pipes, [pid] { return LiveMembers(pid) == 0; });
  pipes.Close();
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  outcome.exit_status = WIFEXITED(status)     ? WEXITSTATUS(status)
                        : WIFSIGNALED(status) ? 128 + WTERMSIG(status)
                                              : 127;
  outcome.out = pipes.out();
  outcome.err = pipes.err();
  return outcome;
}

}  // namespace

void HandOff::Validate() const {
  if (command.empty()) return;
  if (!std::filesystem::path(command.front()).is_absolute()) {
    throw OptionsError("HandOff.command[0] = " + command.front() +
                       "; must be an absolute path (a service's PATH is not a shell's)");
  }
  bool names_session = false;
  for (const std::string& argument : command) {
    names_session = names_session || argument.find("{session}") != std::string::npos ||
                    argument.find("{name}") != std::string::npos;
  }
  if (!names_session) {
    throw OptionsError(
        "HandOff.command names no session; must contain \"{session}\" or \"{name}\"");
  }
  if (!std::isfinite(timeout_s) || timeout_s <= 0) {
    throw OptionsError("HandOff.timeout_s = " + std::to_string(timeout_s) +
                       "; must be a positive number of seconds");
  }
}

std::vector<std::string> HandOffCommand(const HandOff& hand_off,
                                        const std::filesystem::path& session_dir,
                                        const std::string& name) {
  std::vector<std::string> argv = hand_off.command;
  const std::string session = std::filesystem::absolute(session_dir).lexically_normal().string();
  for (std::string& argument : argv) argument = Substitute(argument, session, name);
  return argv;
}

std::string RunHandOff(const HandOff& hand_off, const std::filesystem::path& session_dir,
                       const std::string& name, const std::atomic<bool>* stop) {
  const std::vector<std::string> argv = HandOffCommand(hand_off, session_dir, name);
  if (argv.empty()) throw Error("RunHandOff: no command configured");
  const Outcome run = RunInOwnGroup(argv, hand_off.timeout_s, stop);
  std::string line;
  if (run.ended.empty()) {
    line = "session " + name + " handed off: " + ShellQuoted(argv) + " exited " +
           std::to_string(run.exit_status);
    if (run.exit_status != 0) line += ": " + LastLine(run.err.empty() ? run.out : run.err);
  } else {
    line = "session " + name + " hand-off " + run.ended + ": " + ShellQuoted(argv) +
           " (exit status " + std::to_string(run.exit_status) + "); run it again by hand";
  }
  if (run.leftovers > 0) {
    line += "; ended " + std::to_string(run.leftovers) +
            " process(es) it left running in its process group";
  }
  return line;
}

}  // namespace brdfrig::acquire
