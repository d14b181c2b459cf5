// brdfrig: one command, one subcommand per job. Each subcommand is registered by a
// Register*Commands function (apps/brdfrig/*_commands.cc) that only parses options and calls
// a library function; errors a user can fix are printed as one clear line, exit code 1.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>

#include "apps/brdfrig/acquire_commands.h"
#include "apps/brdfrig/batch_commands.h"
#include "apps/brdfrig/daemon_commands.h"
#include "apps/brdfrig/evaluate_commands.h"
#include "apps/brdfrig/prior_commands.h"
#include "apps/brdfrig/reconstruct_commands.h"
#include "apps/brdfrig/render_commands.h"
#include "apps/brdfrig/rig_commands.h"
#include "apps/brdfrig/sim_commands.h"
#include "apps/brdfrig/target_commands.h"
#include "common/error.h"
#include "rig/hardware_backends.h"
#include "sim/devices.h"

int main(int argc, char** argv) {
  CLI::App app{"brdfrig: measure how a flat material reflects light"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("brdfrig ") + BRDFRIG_VERSION);
  brdfrig::apps::RegisterSimCommands(app);
  brdfrig::apps::RegisterRenderCommands(app);
  brdfrig::apps::RegisterReconstructCommands(app);
  brdfrig::apps::RegisterBatchCommands(app);
  brdfrig::apps::RegisterEvaluateCommands(app);
  brdfrig::apps::RegisterPriorCommands(app);
  brdfrig::apps::RegisterRigCommands(app);
  brdfrig::apps::RegisterTargetCommands(app);
  brdfrig::apps::RegisterAcquireCommands(app);
  brdfrig::apps::RegisterDaemonCommands(app);
  brdfrig::sim::RegisterSimBackends();
  brdfrig::rig::RegisterHardwareBackends();

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const brdfrig::Error& e) {
    std::fprintf(stderr, "brdfrig: error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "brdfrig: internal error: %s\n", e.what());
    return 2;
  }
  return 0;
}
