// `brdfrig target print`: parses options and calls calibrate/print_targets.h.
#pragma once

#include <CLI/CLI.hpp>

namespace brdfrig::apps {

void RegisterTargetCommands(CLI::App& app);

}  // namespace brdfrig::apps
