// `brdfrig prior build` and `brdfrig prior show`: parse options and call prior/.
#pragma once

#include <CLI/CLI.hpp>

namespace brdfrig::apps {

void RegisterPriorCommands(CLI::App& app);

}  // namespace brdfrig::apps
