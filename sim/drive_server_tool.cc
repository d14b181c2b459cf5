#include "sim/drive_server_tool.h"

#include <signal.h>

#include <cstdio>

#include "common/error.h"
#include "sim/modbus_drive_server.h"

namespace brdfrig::sim {

void SimDriveOptions::Validate() const {
  if ((tcp_port >= 0) == pty) {
    throw OptionsError("rig simdrive: give exactly one of --tcp PORT and --pty");
  }
  if (tcp_port > 65535) throw OptionsError("rig simdrive: --tcp port must be 0..65535");
  if (slave < 1 || slave > 247) throw OptionsError("rig simdrive: --slave must be 1..247");
  if (faults.drop_responses < 0 || faults.corrupt_responses < 0 || faults.exception_responses < 0) {
    throw OptionsError("rig simdrive: fault counts must be >= 0");
  }
  if (faults.alarm_at_fraction > 1) throw OptionsError("rig simdrive: --alarm-at must be 0..1");
  if (!(faults.speed_factor > 0)) throw OptionsError("rig simdrive: --slow must be > 0");
}

void RunSimulatedDrive(const SimDriveOptions& options) {
  options.Validate();
  DriveServerOptions server_options;
  server_options.transport =
      options.pty ? DriveServerOptions::Transport::kPty : DriveServerOptions::Transport::kTcp;
  server_options.tcp_port = std::max(0, options.tcp_port);
  server_options.slave = options.slave;
  const rig::DriveProfile profile = rig::LoadDriveProfile(options.profile);

  // Block the signals before the server thread starts so that only sigwait below sees them.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  sigset_t previous;
  pthread_sigmask(SIG_BLOCK, &signals, &previous);
  {
    ModbusDriveServer server(profile, server_options);
    server.InjectFaults(options.faults);
    std::printf("simulated drive (profile %s, slave %d) serving on %s\n", profile.name.c_str(),
                options.slave, server.Endpoint().c_str());
    if (options.pty) {
      std::printf(
          "rig.yaml: {backend: modbus, transport: rtu, device: %s, slave: %d, "
          "profile: %s}\n",
          server.pty_path().c_str(), options.slave, profile.name.c_str());
    } else {
      std::printf(
          "rig.yaml: {backend: modbus, transport: tcp, host: 127.0.0.1, port: %d, "
          "slave: %d, profile: %s}\n",
          server.port(), options.slave, profile.name.c_str());
    }
    std::printf("Ctrl-C to stop\n");
    std::fflush(stdout);
    int received = 0;
    sigwait(&signals, &received);
    const DriveServerCounters c = server.counters();
    std::printf(
        "stopped: %d requests (%d dropped, %d corrupted, %d exceptions), %d moves, %d stops, "
        "final position %d steps\n",
        c.requests, c.dropped, c.corrupted, c.exceptions, c.moves, c.stops,
        server.position_steps());
  }
  pthread_sigmask(SIG_SETMASK, &previous, nullptr);
}

}  // namespace brdfrig::sim
