// `brdfrig reconstruct`: parses options and calls reconstruct::ReconstructBatch; the
// reconstruction flags shared with `brdfrig batch prepare`.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "reconstruct/batch.h"

namespace brdfrig::apps {

// The reconstruction flags `brdfrig reconstruct` and `brdfrig batch prepare` share, so that a
// job array fits with exactly the settings a local run would.
struct ReconstructFlags {
  bool force = false;
  double bin_width_deg = 0.02;
  bool light_refine = false;
  bool strict = false;
  std::string model;
};
void AddReconstructFlags(CLI::App* cmd, ReconstructFlags& flags);
void ApplyReconstructFlags(const ReconstructFlags& flags, reconstruct::BatchOptions& options);

void RegisterReconstructCommands(CLI::App& app);

}  // namespace brdfrig::apps
