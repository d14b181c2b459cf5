// `brdfrig rig simdrive`: runs the simulated Modbus drive in the foreground for manual checks
// of a rig.yaml, `brdfrig rig move` or another Modbus client, until SIGINT/SIGTERM.
#pragma once

#include <string>

#include "sim/modbus_drive_server.h"

namespace brdfrig::sim {

struct SimDriveOptions {
  std::string profile = "oriental_az_direct";  // name of a shipped profile or a .yaml path
  int tcp_port = -1;                           // >= 0: serve TCP on 127.0.0.1 (0: any port)
  bool pty = false;                            // serve RTU on a new pseudo-terminal
  int slave = 1;
  DriveFaults faults;     // injected at start, to rehearse what an operator will see
  void Validate() const;  // exactly one of TCP and pty; throws OptionsError
};

// Prints where it serves and the rig.yaml lines to reach it, then blocks until SIGINT or
// SIGTERM (which it handles itself while running).
void RunSimulatedDrive(const SimDriveOptions& options);

}  // namespace brdfrig::sim
