// `brdfrig rig check|move|shoot|simdrive`: parses options and calls rig/rig_tools.h and
// sim/drive_server_tool.h.
#pragma once

#include <CLI/CLI.hpp>

namespace brdfrig::apps {

void RegisterRigCommands(CLI::App& app);

}  // namespace brdfrig::apps
