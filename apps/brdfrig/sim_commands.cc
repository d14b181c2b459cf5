#include "apps/brdfrig/sim_commands.h"

#include <cstdio>
#include <memory>

#include "sim/scene.h"
#include "sim/simulate.h"

namespace brdfrig::apps {
namespace {

struct SimulateArgs {
  std::string scene;
  std::string output;
  std::vector<std::string> positions;
  std::vector<double> exposures;
  int threads = 0;
  bool no_truth = false;
};

}  // namespace

void RegisterSimCommands(CLI::App& app) {
  auto args = std::make_shared<SimulateArgs>();
  CLI::App* cmd = app.add_subcommand(
      "simulate", "Synthesize a bracketed capture of a scene with the simulated rig");
  cmd->add_option("scene", args->scene, "Scene file (e.g. sim/scenes/default.yaml)")->required();
  cmd->add_option("-o,--output", args->output, "Output directory (photos/ and truth/)")->required();
  cmd->add_option("--positions", args->positions,
                  "Positions as axis=degrees[,axis=degrees...], one per position "
                  "(default: the scene's capture.positions)");
  cmd->add_option("--exposures", args->exposures,
                  "Exposure times in seconds (default: the scene's capture.exposures)");
  cmd->add_option("--threads", args->threads, "Worker threads (0 = all cores)");
  cmd->add_flag("--no-truth", args->no_truth, "Do not write the truth/ folder");
  cmd->callback([args] {
    sim::SimulateOptions options;
    options.scene = args->scene;
    options.output_dir = args->output;
    for (const std::string& p : args->positions) {
      options.positions.push_back(sim::ParsePositionsDegrees(p));
    }
    options.exposures = args->exposures;
    options.threads = args->threads;
    options.write_truth = !args->no_truth;
    const sim::SimulateSummary summary = sim::Simulate(options);
    std::printf("%s\n", summary.ToString().c_str());
  });
}

}  // namespace brdfrig::apps
