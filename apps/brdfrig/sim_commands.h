// `brdfrig simulate`: parses options and calls sim::Simulate.
#pragma once

#include <CLI/CLI.hpp>

namespace brdfrig::apps {

void RegisterSimCommands(CLI::App& app);

}  // namespace brdfrig::apps
