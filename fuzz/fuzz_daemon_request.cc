// The daemon's control API: requests as the HTTP server hands them to Daemon::Handle (method,
// path, JSON body with a plan.yaml text inside), on a daemon that owns a simulated rig.
// Input: "METHOD PATH\n" then the body. Anything but an answer below 500 is a finding: a
// client must get a 4xx for whatever it sends, and nothing may escape the handler.
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>

#include "acquire/daemon.h"
#include "fuzz/fuzz_input.h"
#include "sim/devices.h"

namespace {

namespace fs = std::filesystem;

constexpr const char* kRig = R"(geometry: scene.yaml
camera: {backend: sim, scene: scene.yaml}
axes:
  camera_arm: {backend: sim, scene: scene.yaml}
  light_arm: {backend: sim, scene: scene.yaml}
light: {backend: sim, scene: scene.yaml}
)";

brdfrig::acquire::DaemonConfig MakeConfig() {
  brdfrig::sim::RegisterSimBackends();
  brdfrig::fuzz::WriteScratchFile("scene.yaml", brdfrig::fuzz::kSmallScene);
  brdfrig::acquire::DaemonConfig config;
  config.rig_file = brdfrig::fuzz::WriteScratchFile("rig.yaml", kRig);
  config.data_dir = brdfrig::fuzz::ScratchDir() / "data";
  // sun_path holds 107 bytes: the socket gets a short name of its own.
  config.socket = "/tmp/brdfrig-fuzz-" + std::to_string(::getpid()) + ".sock";
  config.run.retry.initial_backoff_s = 0.001;
  return config;
}

brdfrig::acquire::Daemon& TheDaemon() {
  static brdfrig::acquire::Daemon daemon(MakeConfig());
  return daemon;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  brdfrig::acquire::Daemon& daemon = TheDaemon();
  const std::string input = brdfrig::fuzz::AsString(data, size);
  const std::size_t space = input.find(' '), newline = input.find('\n');
  brdfrig::acquire::HttpRequest request;
  if (space != std::string::npos && newline != std::string::npos && space < newline) {
    request.method = input.substr(0, space);
    request.path = input.substr(space + 1, newline - space - 1);
    request.body = input.substr(newline + 1);
  } else {
    request.method = "POST";
    request.path = "/v1/sessions";
    request.body = input;
  }
  const brdfrig::acquire::HttpResponse response = daemon.Handle(request);
  if (response.status >= 500) {
    std::fprintf(stderr, "internal error %d for a client request: %s\n", response.status,
                 response.body.c_str());
    std::abort();
  }
  // An accepted plan runs on the simulated rig; its session is removed afterwards so that the
  // data directory stays small over millions of inputs.
  daemon.WaitIdle();
  if (response.status == 201) {
    const auto answer = nlohmann::json::parse(response.body);
    fs::remove_all(daemon.config().data_dir / answer.at("name").get<std::string>());
  }
  return 0;
}
