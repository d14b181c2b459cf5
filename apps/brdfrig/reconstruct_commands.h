// `brdfrig reconstruct`: parses options and calls reconstruct::ReconstructBatch.
#pragma once

#include <CLI/CLI.hpp>

namespace brdfrig::apps {

void RegisterReconstructCommands(CLI::App& app);

}  // namespace brdfrig::apps
