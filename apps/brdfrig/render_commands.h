#pragma once

#include <CLI/CLI.hpp>

namespace brdfrig::apps {

// `brdfrig render` (headless), `brdfrig view` (window) and `brdfrig export` (MERL table).
void RegisterRenderCommands(CLI::App& app);

}  // namespace brdfrig::apps
