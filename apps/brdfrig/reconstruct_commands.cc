#include "apps/brdfrig/reconstruct_commands.h"

#include <cstdio>
#include <memory>

#include "common/angles.h"
#include "common/error.h"
#include "reconstruct/batch.h"

namespace brdfrig::apps {
namespace {

struct ReconstructArgs {
  std::vector<std::string> inputs;
  std::string output;
  int jobs = 2;
  ReconstructFlags flags;
};

}  // namespace

void AddReconstructFlags(CLI::App* cmd, ReconstructFlags& flags) {
  cmd->add_flag("--force", flags.force, "Redo captures whose output is up to date");
  cmd->add_option(
      "--bin-width-deg", flags.bin_width_deg,
      "Average samples in bins of this many degrees of theta (0 = every pixel; default 0.02)");
  cmd->add_option("--model", flags.model,
                  "Model kind to fit: seed, seed_constrained, microfacet, ggx, beckmann "
                  "(default: every rung of the ladder, the best by leave-one-position-out "
                  "validation)");
  cmd->add_flag("--strict", flags.strict,
                "Fail a capture (write nothing for it) when any of its positions would be "
                "dropped or degraded (NaN/Inf pixels, or a sample below the noise floor); exit "
                "status 1 instead of 3");
  cmd->add_flag("--light-refine", flags.light_refine,
                "Refine the highlight's light jointly with a lobe symmetric about the mirror "
                "direction (off by default: it biases the light under grazing light, "
                "reconstruct/light_refine.h)");
}

void ApplyReconstructFlags(const ReconstructFlags& flags, reconstruct::BatchOptions& options) {
  options.force = flags.force;
  options.reconstruct.samples.bin_width = Radians(flags.bin_width_deg);
  options.reconstruct.light_refine.enabled = flags.light_refine;
  options.reconstruct.model = flags.model;
  options.reconstruct.strict = flags.strict;
}

void RegisterReconstructCommands(CLI::App& app) {
  auto args = std::make_shared<ReconstructArgs>();
  CLI::App* cmd = app.add_subcommand(
      "reconstruct", "Fit a material model (material.json) to the photos of one or many captures");
  cmd->add_option("captures", args->inputs,
                  "Capture directories (sessions or `brdfrig simulate` output), or directories "
                  "holding captures")
      ->required();
  cmd->add_option("-o,--output", args->output,
                  "material.json (one capture) or a directory (one subdirectory per capture)")
      ->required();
  cmd->add_option("-j,--jobs", args->jobs, "Captures reconstructed at once");
  AddReconstructFlags(cmd, args->flags);
  cmd->callback([args] {
    reconstruct::BatchOptions options;
    for (const std::string& input : args->inputs) options.inputs.emplace_back(input);
    options.output = args->output;
    options.jobs = args->jobs;
    ApplyReconstructFlags(args->flags, options);
    const auto items = reconstruct::ReconstructBatch(
        options, [](const std::string& message) { std::fprintf(stderr, "%s\n", message.c_str()); });
    for (const auto& item : items) {
      const bool failed = item.status == reconstruct::BatchItem::Status::kFailed;
      std::printf("%-10s %s -> %s (%.1f s)%s%s\n", item.StatusName().c_str(),
                  item.input.string().c_str(), item.material_file.string().c_str(), item.seconds,
                  failed ? ": " : "", failed ? item.message.c_str() : "");
      for (const std::string& d : item.dropped) std::printf("           dropped %s\n", d.c_str());
      for (const std::string& d : item.degraded) {
        std::printf("           degraded %s\n", d.c_str());
      }
      if (!item.ladder.empty()) std::printf("%s", item.ladder.c_str());
    }
    // Exit statuses (README): 0 complete, 3 written with dropped or degraded positions, 1 failed.
    switch (reconstruct::BatchExitStatus(items)) {
      case 0:
        return;
      case 3:
        std::fprintf(stderr,
                     "brdfrig: warning: material(s) written without some positions or from "
                     "damaged photos (listed above); exit status 3 (--strict makes this a "
                     "failure)\n");
        throw CLI::RuntimeError(3);
      default: {
        int failed = 0;
        for (const auto& item : items) {
          failed += item.status == reconstruct::BatchItem::Status::kFailed;
        }
        throw Error(std::to_string(failed) + " capture(s) failed (see above)");
      }
    }
  });
}

}  // namespace brdfrig::apps
