// `brdfrig rig simcamera`: runs the simulated PTP/IP camera in the foreground (for the gphoto2
// tool, a rig.yaml with `port: ptpip:...`, or a whole simulated lab on loopback) until SIGINT or
// SIGTERM.
#pragma once

#include <string>

#include "simcamera/ptpip_server.h"

namespace brdfrig::simcamera {

struct SimCameraOptions {
  std::string listen = "127.0.0.1:15740";  // HOST:PORT; port 0 picks a free one
  std::string scene;                       // scene file: what the camera photographs
  std::string rig;        // optional rig.yaml whose axes (drives) give the pose of each shot
  int threads = 0;        // rendering threads (0: all)
  CameraFaults faults;    // injected at start, to rehearse what an operator will see
  void Validate() const;  // throws OptionsError
};

// The shutter speeds the camera offers when the scene lists none: 1/3 stops, 30 s … 1/4000 s.
std::vector<double> DefaultShutterSpeeds();

// Prints where it serves and the rig.yaml line to reach it, then blocks until SIGINT or
// SIGTERM (which it handles itself while running).
void RunSimulatedCamera(const SimCameraOptions& options);

}  // namespace brdfrig::simcamera
