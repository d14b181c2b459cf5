// `brdfrig batch prepare|submit|run|status|collect`: parses options and calls batch/.
#pragma once

#include <CLI/CLI.hpp>

namespace brdfrig::apps {

void RegisterBatchCommands(CLI::App& app);

}  // namespace brdfrig::apps
