// `brdfrig daemon` and its clients `brdfrig submit|status|pause|resume|abort`: parse options
// and call the acquire library (acquire/daemon.h, acquire/daemon_client.h).
#pragma once

#include <CLI/CLI.hpp>

namespace brdfrig::apps {

void RegisterDaemonCommands(CLI::App& app);

}  // namespace brdfrig::apps
