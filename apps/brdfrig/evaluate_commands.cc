#include "apps/brdfrig/evaluate_commands.h"

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "jobs/demo.h"
#include "jobs/evaluate_job.h"

namespace brdfrig::apps {
namespace {

struct DemoArgs {
  std::string scene;
  std::string output = "demo-out";
};

struct EvaluateArgs {
  std::string material, scene, capture, output = "evaluate-out";
  std::vector<int> positions;
  std::vector<double> elevations_deg = {20, 40, 60, 75};
  std::vector<double> phis_deg = {0, 45, 90, 180};
  bool linear = false;
};

void Progress(const std::string& m) { std::fprintf(stderr, "%s\n", m.c_str()); }

}  // namespace

void RegisterEvaluateCommands(CLI::App& app) {
  auto args = std::make_shared<DemoArgs>();
  CLI::App* cmd = app.add_subcommand(
      "demo", "Simulated capture → reconstruction → held-out renders → report, no hardware");
  cmd->add_option("--scene", args->scene, "Scene file (default: the built-in default scene)");
  cmd->add_option("-o,--output", args->output, "Report directory");
  cmd->callback([args] {
    jobs::DemoOptions options;
    options.scene = args->scene;
    options.output_dir = args->output;
    options.progress = Progress;
    const jobs::DemoSummary summary = jobs::RunDemo(options);
    std::printf("%s\nreport: %s\n", summary.text.c_str(), summary.report_html.string().c_str());
  });

  auto eval = std::make_shared<EvaluateArgs>();
  CLI::App* ev = app.add_subcommand(
      "evaluate",
      "Judge a material against a simulated scene's truth (held-out views, sphere, BRDF error) "
      "and/or a capture's validation photos");
  ev->add_option("material", eval->material, "material.json to evaluate")->required();
  ev->add_option("--scene", eval->scene, "Scene whose sample is the truth");
  ev->add_option("--capture", eval->capture,
                 "Capture (session or `brdfrig simulate` output) whose validation photos are "
                 "compared with the material under their measured geometry");
  ev->add_option("--positions", eval->positions,
                 "Capture positions to compare (default: the plan's validation positions)")
      ->delimiter(',');
  ev->add_option("-o,--output", eval->output, "Report directory");
  ev->add_option("--elevation", eval->elevations_deg,
                 "Camera and light elevations of the held-out views (degrees)")
      ->delimiter(',');
  ev->add_option("--phi", eval->phis_deg, "Light azimuths of the held-out views (degrees)")
      ->delimiter(',');
  ev->add_flag("--linear", eval->linear, "Render with the seed's linear interpolation");
  ev->callback([eval] {
    jobs::EvaluateOptions options;
    options.material = eval->material;
    options.scene = eval->scene;
    options.capture = eval->capture;
    options.positions = eval->positions;
    options.output_dir = eval->output;
    options.view_elevations_deg = eval->elevations_deg;
    options.view_phis_deg = eval->phis_deg;
    options.linear_interpolation = eval->linear;
    options.progress = Progress;
    const jobs::EvaluateSummary summary = jobs::RunEvaluate(options);
    std::printf("%s\nreport: %s\n", summary.text.c_str(), summary.report_html.string().c_str());
  });
}

}  // namespace brdfrig::apps
