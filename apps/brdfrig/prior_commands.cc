#include "apps/brdfrig/prior_commands.h"

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "prior/build_prior.h"
#include "prior/measured_prior.h"

namespace brdfrig::apps {
namespace {

struct BuildArgs {
  std::vector<std::string> directories;
  std::string output;
  prior::PriorBuildOptions options;
};

}  // namespace

void RegisterPriorCommands(CLI::App& app) {
  CLI::App* prior_cmd = app.add_subcommand(
      "prior", "The measured prior the fit fills unobserved directions from (docs/prior.md)");
  prior_cmd->require_subcommand(1);

  auto args = std::make_shared<BuildArgs>();
  CLI::App* build = prior_cmd->add_subcommand(
      "build", "Build a prior from directories of measured materials (nbrdf-mlp *.json)");
  build->add_option("directories", args->directories, "Directories of measured materials")
      ->required();
  build->add_option("-o,--output", args->output, "The prior file to write")->required();
  build->add_option("--name", args->options.name, "Name recorded in the prior");
  build->add_option("--components", args->options.max_components,
                    "Principal components kept (at most the training channels - 1)");
  build->add_option("--noise", args->options.noise_sigma,
                    "Noise level of one sample's ln value (unit weight) recorded for the fit");
  build->add_option("--correction-weight", args->options.correction_weight,
                    "How much data it takes to move a table node off the prior");
  build->add_option("--exclude", args->options.exclude, "Material names to leave out")
      ->delimiter(',');
  build->add_option("--theta-h", args->options.grid.theta_h, "Table nodes in theta_h");
  build->add_option("--theta-d", args->options.grid.theta_d, "Table nodes in theta_d");
  build->add_option("--phi-d", args->options.grid.phi_d, "Table nodes in phi_d");
  build->callback([args] {
    std::vector<std::filesystem::path> dirs(args->directories.begin(), args->directories.end());
    const prior::TrainingSet set = prior::ReadTrainingSet(dirs, args->options);
    const prior::MeasuredPrior p = prior::BuildPrior(set, args->options);
    prior::WritePrior(p, args->output);
    std::printf("prior '%s': %zu training materials, %d components, grid %d x %d x %d -> %s\n",
                p.name.c_str(), p.training.size(), p.Components(), p.grid.theta_h, p.grid.theta_d,
                p.grid.phi_d, args->output.c_str());
  });

  auto path = std::make_shared<std::string>();
  CLI::App* show = prior_cmd->add_subcommand("show", "What a prior holds and what built it");
  show->add_option("prior", *path, "Prior file (default: the shipped one)");
  show->callback([path] {
    const std::filesystem::path file =
        path->empty() ? prior::DefaultPriorPath() : std::filesystem::path(*path);
    const prior::MeasuredPrior p = prior::ReadPrior(file);
    std::printf("%s: prior '%s' (format version %d, %s)\n", file.c_str(), p.name.c_str(), p.version,
                p.built_with.c_str());
    std::printf(
        "grid %d x %d x %d (theta_h sqrt-spaced, theta_d, phi_d), epsilon %g, cosine "
        "floor %g; %d components; noise %g; correction weight %g\n",
        p.grid.theta_h, p.grid.theta_d, p.grid.phi_d, p.grid.epsilon, p.grid.cos_floor,
        p.Components(), p.noise_sigma, p.correction_weight);
    std::printf("%zu training materials:\n", p.training.size());
    for (const prior::TrainingMaterial& m : p.training) {
      std::printf("  %-32s %-5s %s  %s\n", m.name.c_str(), m.database.c_str(),
                  m.sha256.substr(0, 12).c_str(), m.licence.c_str());
    }
  });
}

}  // namespace brdfrig::apps
