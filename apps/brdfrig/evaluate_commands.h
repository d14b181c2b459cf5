// `brdfrig demo` and `brdfrig evaluate`: parse options and call jobs::RunDemo / RunEvaluate.
#pragma once

#include <CLI/CLI.hpp>

namespace brdfrig::apps {

void RegisterEvaluateCommands(CLI::App& app);

}  // namespace brdfrig::apps
