// A private single-node Slurm cluster for tests: munged with a generated key, slurmctld and
// slurmd with a generated slurm.conf, every socket, state and log file in one temporary
// directory, listening on loopback ports picked free, running as the current user. No system
// service, configuration or state is touched; commands reach it through SLURM_CONF, which
// Start() sets for this process and its children.
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <memory>
#include <string>

namespace brdfrig::batch::testing {

class PrivateSlurm {
 public:
  // Why this machine cannot run the cluster: the programs it needs that are missing (""
  // when all are installed).
  static std::string MissingPrograms();

  // Starts the three daemons under a new directory in $TMPDIR and waits (up to `timeout_s`)
  // until the node is idle. Throws std::runtime_error with the daemons' log tails otherwise.
  static std::unique_ptr<PrivateSlurm> Start(double timeout_s = 60);

  // Stops the daemons it started (by their pid files), waiting for them to exit.
  ~PrivateSlurm();
  PrivateSlurm(const PrivateSlurm&) = delete;
  PrivateSlurm& operator=(const PrivateSlurm&) = delete;

  const std::filesystem::path& dir() const { return dir_; }
  std::filesystem::path conf() const { return dir_ / "slurm.conf"; }
  int cpus() const { return cpus_; }
  // The last lines of every daemon log, for a failure message.
  std::string LogTails() const;

 private:
  explicit PrivateSlurm(std::filesystem::path dir) : dir_(std::move(dir)) {}
  void WriteConfiguration();
  void StartDaemons(double timeout_s);
  void Stop(const std::filesystem::path& pid_file);

  std::filesystem::path dir_;
  int cpus_ = 1;
};

}  // namespace brdfrig::batch::testing
