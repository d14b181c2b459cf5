// daemon.yaml's `hand_off`: a command the daemon runs after each session that completes, so
// that capture → fit runs unattended. The daemon knows nothing of what the command does (it
// is typically `brdfrig batch prepare <session> ... --submit`, which hands the session to the
// cluster's scheduler, docs/slurm.md); it only runs it, without a shell, and logs its outcome.
//
//   hand_off:
//     command: [/usr/local/bin/brdfrig, batch, prepare, "{session}", -o, /srv/fits,
//               --job-dir, "/srv/jobs/{name}", --partition, lab, --submit]
//     timeout_s: 600
//
// "{session}" becomes the session's directory (absolute), "{name}" its name, in any argument;
// each placeholder is replaced once, in the command as written (never inside what another one
// became).
//
// The command runs in a process group of its own. When it exits, whatever it left running in
// that group is ended (SIGTERM, SIGKILL after kHandOffGraceS): a background child holding its
// output must not keep the daemon waiting, nor outlive it unattended. A command that means to
// leave work running hands it to a scheduler (or detaches with setsid). A command still
// running after timeout_s, or when the daemon stops, is ended the same way.
#pragma once

#include <atomic>
#include <filesystem>
#include <string>
#include <vector>

namespace brdfrig::acquire {

// Seconds between SIGTERM and SIGKILL to a hand-off's process group.
inline constexpr double kHandOffGraceS = 2.0;

struct HandOff {
  std::vector<std::string> command;  // empty: no hand-off
  double timeout_s = 600;            // the command is ended after this long
  bool enabled() const { return !command.empty(); }
  // The program must be an absolute path (a service's PATH is not the lab's shell's), some
  // argument must name the session ("{session}" or "{name}") and timeout_s must be positive.
  void Validate() const;
};

// The command for one session, placeholders replaced.
std::vector<std::string> HandOffCommand(const HandOff& hand_off,
                                        const std::filesystem::path& session_dir,
                                        const std::string& name);

// Runs it and waits until it exits, times out, or `stop` becomes true (the daemon stopping);
// returns one line for the daemon's log: the command, its exit status, the last line it wrote
// to stderr when it failed, and what had to be ended.
std::string RunHandOff(const HandOff& hand_off, const std::filesystem::path& session_dir,
                       const std::string& name, const std::atomic<bool>* stop = nullptr);

}  // namespace brdfrig::acquire
