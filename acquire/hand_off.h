// daemon.yaml's `hand_off`: a command the daemon runs after each session that completes, so
// that capture → fit runs unattended. The daemon knows nothing of what the command does (it
// is typically `brdfrig batch prepare <session> ... --submit`, which hands the session to the
// cluster's scheduler, docs/slurm.md); it only runs it, without a shell, and logs its outcome.
//
//   hand_off:
//     command: [/usr/local/bin/brdfrig, batch, prepare, "{session}", -o, /srv/fits,
//               --job-dir, "/srv/jobs/{name}", --partition, lab, --submit]
//
// "{session}" becomes the session's directory (absolute), "{name}" its name, in any argument.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace brdfrig::acquire {

struct HandOff {
  std::vector<std::string> command;  // empty: no hand-off
  bool enabled() const { return !command.empty(); }
  // The program must be an absolute path (a service's PATH is not the lab's shell's) and some
  // argument must name the session ("{session}" or "{name}").
  void Validate() const;
};

// The command for one session, placeholders replaced.
std::vector<std::string> HandOffCommand(const HandOff& hand_off,
                                        const std::filesystem::path& session_dir,
                                        const std::string& name);

// Runs it and waits; returns one line for the daemon's log: the command, its exit status and
// the last line it wrote to stderr when it failed.
std::string RunHandOff(const HandOff& hand_off, const std::filesystem::path& session_dir,
                       const std::string& name);

}  // namespace brdfrig::acquire
