#include "apps/brdfrig/evaluate_commands.h"

#include <cstdio>
#include <memory>

#include "evaluate/demo.h"

namespace brdfrig::apps {
namespace {

struct DemoArgs {
  std::string scene;
  std::string output = "demo-out";
};

}  // namespace

void RegisterEvaluateCommands(CLI::App& app) {
  auto args = std::make_shared<DemoArgs>();
  CLI::App* cmd = app.add_subcommand(
      "demo", "Simulated capture → reconstruction → held-out renders → report, no hardware");
  cmd->add_option("--scene", args->scene, "Scene file (default: the built-in default scene)");
  cmd->add_option("-o,--output", args->output, "Report directory");
  cmd->callback([args] {
    evaluate::DemoOptions options;
    options.scene = args->scene;
    options.output_dir = args->output;
    options.progress = [](const std::string& m) { std::fprintf(stderr, "%s\n", m.c_str()); };
    const evaluate::DemoSummary summary = evaluate::RunDemo(options);
    std::printf("%s\nreport: %s\n", summary.text.c_str(), summary.report_html.string().c_str());
  });
}

}  // namespace brdfrig::apps
