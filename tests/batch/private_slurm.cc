#include "tests/batch/private_slurm.h"

#include <netinet/in.h>
#include <pwd.h>
#include <signal.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <random>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <vector>

#include "common/subprocess.h"

namespace brdfrig::batch::testing {

namespace fs = std::filesystem;

namespace {

// The programs the cluster and the tests need (Debian: munge, slurm-wlm, slurm-client).
constexpr std::array<const char*, 7> kPrograms = {"munged", "slurmctld", "slurmd", "sbatch",
                                                  "squeue", "scancel",   "sinfo"};

bool InPath(const std::string& program) {
  const char* path = std::getenv("PATH");
  std::istringstream dirs(std::string(path ? path : "") + ":/usr/sbin:/sbin");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    if (!dir.empty() && ::access((fs::path(dir) / program).c_str(), X_OK) == 0) return true;
  }
  return false;
}

// A loopback port nobody listens on now. Another program may take it before the daemon binds
// it; the daemons then fail to start and say so in their logs.
int FreePort() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t size = sizeof address;
  if (fd < 0 || ::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0 ||
      ::getsockname(fd, reinterpret_cast<sockaddr*>(&address), &size) != 0) {
    if (fd >= 0) ::close(fd);
    throw std::runtime_error("cannot find a free loopback port");
  }
  const int port = ntohs(address.sin_port);
  ::close(fd);
  return port;
}

std::string ShortHostName() {
  std::array<char, 256> name{};
  ::gethostname(name.data(), name.size() - 1);
  std::string host = name.data();
  return host.substr(0, host.find('.'));
}

std::string UserName() {
  const passwd* pw = ::getpwuid(::geteuid());
  if (pw == nullptr) throw std::runtime_error("the current user has no name (getpwuid)");
  return pw->pw_name;
}

std::string Tail(const fs::path& file, int lines) {
  std::ifstream in(file);
  std::vector<std::string> all;
  for (std::string line; std::getline(in, line);) all.push_back(line);
  std::string tail;
  for (std::size_t i = all.size() > static_cast<std::size_t>(lines) ? all.size() - lines : 0;
       i < all.size(); ++i) {
    tail += "  " + all[i] + "\n";
  }
  return tail;
}

void Run(const std::vector<std::string>& argv) {
  const ProcessResult run = RunProcess(argv);
  if (!run.ok()) {
    throw std::runtime_error(ShellQuoted(argv) + " failed (exit status " +
                             std::to_string(run.exit_status) + "): " + run.err + run.out);
  }
}

}  // namespace

std::string PrivateSlurm::MissingPrograms() {
  std::string missing;
  for (const char* program : kPrograms) {
    if (!InPath(program)) missing += (missing.empty() ? "" : ", ") + std::string(program);
  }
  return missing;
}

std::unique_ptr<PrivateSlurm> PrivateSlurm::Start(double timeout_s) {
  // Unix socket paths are limited to 108 bytes: a deep $TMPDIR falls back to /tmp.
  std::string base = (fs::temp_directory_path() / "slurm-XXXXXX").string();
  if (base.size() > 70) base = "/tmp/brdfrig-slurm-XXXXXX";
  std::vector<char> pattern(base.begin(), base.end());
  pattern.push_back('\0');
  if (::mkdtemp(pattern.data()) == nullptr) {
    throw std::runtime_error("cannot create a directory from " + base);
  }
  std::unique_ptr<PrivateSlurm> slurm(new PrivateSlurm(pattern.data()));
  // munged requires its socket's directory to be searchable by all and its key private.
  fs::permissions(slurm->dir_, fs::perms(0755));
  slurm->WriteConfiguration();
  ::setenv("SLURM_CONF", slurm->conf().c_str(), 1);
  slurm->StartDaemons(timeout_s);
  return slurm;
}

void PrivateSlurm::WriteConfiguration() {
  for (const char* sub : {"munge", "ctld", "spool"}) {
    fs::create_directory(dir_ / sub);
    fs::permissions(dir_ / sub, fs::perms(0700));
  }
  {
    std::random_device random;
    std::string key(1024, '\0');
    for (char& c : key) c = static_cast<char>(random());
    std::ofstream(dir_ / "munge" / "munge.key", std::ios::binary) << key;
    fs::permissions(dir_ / "munge" / "munge.key", fs::perms(0400));
  }
  cpus_ = std::max(1u, std::thread::hardware_concurrency());
  const std::string host = ShortHostName(), user = UserName();
  const fs::path d = dir_;
  std::ofstream out(conf());
  out << "ClusterName=brdfrigtest\n"
      << "SlurmctldHost=" << host << "(127.0.0.1)\n"
      << "SlurmctldPort=" << FreePort() << "\n"
      << "SlurmdPort=" << FreePort() << "\n"
      << "AuthType=auth/munge\nCredType=cred/munge\n"
      << "AuthInfo=socket=" << (d / "munge.sock").string() << "\n"
      << "SlurmUser=" << user << "\nSlurmdUser=" << user << "\n"
      << "StateSaveLocation=" << (d / "ctld").string() << "\n"
      << "SlurmdSpoolDir=" << (d / "spool").string() << "\n"
      << "SlurmctldPidFile=" << (d / "slurmctld.pid").string() << "\n"
      << "SlurmdPidFile=" << (d / "slurmd.pid").string() << "\n"
      << "SlurmctldLogFile=" << (d / "slurmctld.log").string() << "\n"
      << "SlurmdLogFile=" << (d / "slurmd.log").string()
      << "\n"
      // No cgroups, no accounting daemon: what a container or a CI runner allows.
      << "ProctrackType=proctrack/linuxproc\nTaskPlugin=task/none\n"
      << "JobAcctGatherType=jobacct_gather/none\n"
      << "AccountingStorageType=accounting_storage/none\nJobCompType=jobcomp/none\n"
      << "MpiDefault=none\nSwitchType=switch/none\nMailProg=/bin/true\n"
      << "SchedulerType=sched/builtin\n"
      << "SelectType=select/cons_tres\nSelectTypeParameters=CR_CPU\n"
      << "SlurmdParameters=config_overrides\nReturnToService=2\n"
      << "SlurmctldTimeout=30\nSlurmdTimeout=30\nMinJobAge=600\nKillWait=5\n"
      << "NodeName=brdfrignode NodeHostname=" << host << " NodeAddr=127.0.0.1 CPUs=" << cpus_
      << " State=UNKNOWN\n"
      << "PartitionName=brdfrig Nodes=brdfrignode Default=YES MaxTime=INFINITE State=UP\n";
}

void PrivateSlurm::StartDaemons(double timeout_s) {
  const fs::path d = dir_;
  Run({"munged", "--key-file=" + (d / "munge" / "munge.key").string(),
       "--socket=" + (d / "munge.sock").string(), "--pid-file=" + (d / "munged.pid").string(),
       "--log-file=" + (d / "munged.log").string(),
       "--seed-file=" + (d / "munge" / "munged.seed").string()});
  Run({"slurmctld", "-f", conf().string()});
  Run({"slurmd", "-f", conf().string(), "-N", "brdfrignode"});
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  std::string state;
  while (std::chrono::steady_clock::now() < deadline) {
    const ProcessResult sinfo = RunProcess({"sinfo", "-h", "-N", "-o", "%T"});
    state = sinfo.out + sinfo.err;
    if (sinfo.ok() && sinfo.out.starts_with("idle")) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  throw std::runtime_error("the private Slurm node did not become idle within " +
                           std::to_string(timeout_s) + " s (sinfo: " + state + ")\n" + LogTails());
}

std::string PrivateSlurm::LogTails() const {
  std::string tails;
  for (const char* log : {"munged.log", "slurmctld.log", "slurmd.log"}) {
    tails += (dir_ / log).string() + ":\n" + Tail(dir_ / log, 8);
  }
  return tails;
}

void PrivateSlurm::Stop(const fs::path& pid_file) {
  std::ifstream in(pid_file);
  pid_t pid = 0;
  if (!(in >> pid) || pid <= 1) return;
  if (::kill(pid, SIGTERM) != 0) return;
  for (int i = 0; i < 100 && ::kill(pid, 0) == 0; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  if (::kill(pid, 0) == 0) ::kill(pid, SIGKILL);
}

PrivateSlurm::~PrivateSlurm() {
  RunProcess({"scancel", "--user=" + UserName()});  // our cluster's jobs only (SLURM_CONF)
  Stop(dir_ / "slurmd.pid");
  Stop(dir_ / "slurmctld.pid");
  Stop(dir_ / "munged.pid");
  std::error_code ignored;
  fs::remove_all(dir_, ignored);
}

}  // namespace brdfrig::batch::testing
