// `brdfrig plan check`, `brdfrig capture` and `brdfrig session verify`: parse options and call
// the acquire library.
#pragma once

#include <CLI/CLI.hpp>

namespace brdfrig::apps {

void RegisterAcquireCommands(CLI::App& app);

}  // namespace brdfrig::apps
