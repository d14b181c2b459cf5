#pragma once

#include <CLI/CLI.hpp>

namespace brdfrig::apps {

// `brdfrig render` (headless) and `brdfrig view` (window).
void RegisterRenderCommands(CLI::App& app);

}  // namespace brdfrig::apps
