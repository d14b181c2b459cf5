// `brdfrig demo`: parses options and calls evaluate::RunDemo.
#pragma once

#include <CLI/CLI.hpp>

namespace brdfrig::apps {

void RegisterEvaluateCommands(CLI::App& app);

}  // namespace brdfrig::apps
