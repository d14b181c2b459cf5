// daemon.yaml: what `brdfrig daemon` owns and where it listens.
//
//   data_dir: /var/lib/brdfrig        # sessions are created here and nowhere else
//   rig: /etc/brdfrig/rig.yaml        # relative paths: relative to daemon.yaml
//   socket: /run/brdfrig/daemon.sock  # default <data_dir>/daemon.sock; created with mode 0600
//   resume_interrupted: false         # on start, resume sessions a crash interrupted
//   tcp: {port: 8765, token_file: token}  # optional loopback listener, bearer token required
//   retry: {max_attempts: 5, initial_backoff_s: 0.5, max_backoff_s: 10}
//   hand_off: {command: [/usr/local/bin/brdfrig, batch, prepare, "{session}", ...],
//              timeout_s: 600}        # run after each complete session (acquire/hand_off.h)
#pragma once

#include <filesystem>
#include <string>

#include "acquire/hand_off.h"
#include "acquire/run_engine.h"

namespace brdfrig::acquire {

struct DaemonConfig {
  std::filesystem::path data_dir;
  std::filesystem::path rig_file;
  std::filesystem::path socket;
  bool resume_interrupted = false;
  int tcp_port = 0;   // 0 = no TCP listener
  std::string token;  // required on TCP (read from token_file)
  RunOptions run;
  HandOff hand_off;
  void Validate() const;
};

// Throws FileError (file:line) for malformed or unknown keys.
DaemonConfig LoadDaemonConfig(const std::filesystem::path& file);

}  // namespace brdfrig::acquire
