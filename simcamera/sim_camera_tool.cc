#include "simcamera/sim_camera_tool.h"

#include <signal.h>

#include <cstdio>
#include <memory>

#include "common/error.h"
#include "rig/hardware_backends.h"
#include "sim/scene.h"
#include "simcamera/drive_positions.h"
#include "simcamera/shot_renderer.h"

namespace brdfrig::simcamera {
namespace {

std::pair<std::string, int> SplitHostPort(const std::string& listen) {
  const auto colon = listen.rfind(':');
  if (colon == std::string::npos) {
    throw OptionsError("rig simcamera: --listen must be HOST:PORT, got '" + listen + "'");
  }
  try {
    std::size_t used = 0;
    const int port = std::stoi(listen.substr(colon + 1), &used);
    if (used != listen.size() - colon - 1 || port < 0 || port > 65535) throw std::out_of_range("");
    return {listen.substr(0, colon), port};
  } catch (const std::logic_error&) {
    throw OptionsError("rig simcamera: --listen port must be 0..65535, got '" + listen + "'");
  }
}

}  // namespace

void SimCameraOptions::Validate() const {
  SplitHostPort(listen);
  if (scene.empty()) throw OptionsError("rig simcamera: --scene is required");
  if (threads < 0) throw OptionsError("rig simcamera: --threads must be >= 0");
  if (faults.busy_responses < 0 || faults.drop_downloads < 0) {
    throw OptionsError("rig simcamera: fault counts must be >= 0");
  }
  if (faults.response_delay_s < 0 || faults.vanish_s < 0) {
    throw OptionsError("rig simcamera: --slow and --vanish must be >= 0 seconds");
  }
}

std::vector<double> DefaultShutterSpeeds() {
  std::vector<double> speeds = {30,  25, 20,  15,  13, 10,  8,   6,   5,   4,  3.2,
                                2.5, 2,  1.6, 1.3, 1,  0.8, 0.6, 0.5, 0.4, 0.3};
  for (double d :
       {4,   5,   6,   8,   10,  13,  15,  20,  25,   30,   40,   50,   60,   80,   100, 125,
        160, 200, 250, 320, 400, 500, 640, 800, 1000, 1250, 1600, 2000, 2500, 3200, 4000}) {
    speeds.push_back(1.0 / d);
  }
  return speeds;
}

void RunSimulatedCamera(const SimCameraOptions& options) {
  options.Validate();
  const auto [host, port] = SplitHostPort(options.listen);
  sim::Scene scene = sim::LoadScene(options.scene);

  std::shared_ptr<DrivePositions> drives;
  if (!options.rig.empty()) {
    rig::RegisterHardwareBackends();
    drives = std::make_shared<DrivePositions>(options.rig);
  }
  CameraServerOptions server_options;
  server_options.host = host;
  server_options.port = port;
  server_options.offer.model = scene.sensor.model + " (PTP/IP)";
  server_options.offer.shutter_speeds_s =
      scene.sensor.shutter_speeds.empty() ? DefaultShutterSpeeds() : scene.sensor.shutter_speeds;
  auto renderer = std::make_shared<ShotRenderer>(
      std::move(scene), [drives] { return drives ? drives->Read() : geometry::AxisPositions{}; },
      options.threads);

  // Block the signals before the server thread starts so that only sigwait below sees them.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  sigset_t previous;
  pthread_sigmask(SIG_BLOCK, &signals, &previous);
  {
    PtpIpCameraServer server(server_options,
                             [renderer](const ExposureSettings& e) { return renderer->Shoot(e); });
    server.InjectFaults(options.faults);
    std::printf("simulated PTP/IP camera serving on %s (scene %s%s)\n", server.PortPath().c_str(),
                options.scene.c_str(),
                options.rig.empty() ? ", axes at 0" : (", drives of " + options.rig).c_str());
    std::printf("rig.yaml: camera: {backend: gphoto2, port: \"%s\"}\n", server.PortPath().c_str());
    std::printf("gphoto2 --port %s --camera \"PTP/IP Camera\" --capture-image-and-download\n",
                server.PortPath().c_str());
    std::printf("Ctrl-C to stop\n");
    std::fflush(stdout);
    int received = 0;
    sigwait(&signals, &received);
    const CameraServerCounters c = server.counters();
    std::printf(
        "stopped: %d connections, %d operations, %d captures (%d busy, %d dropped, %d card "
        "full, %d vanished), %zu files on the card, %d connections refused\n",
        c.connections, c.operations, c.captures, c.busy, c.dropped, c.store_full, c.vanished,
        server.files_on_card(), c.refused);
  }
  pthread_sigmask(SIG_SETMASK, &previous, nullptr);
}

}  // namespace brdfrig::simcamera
