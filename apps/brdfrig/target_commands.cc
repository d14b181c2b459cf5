#include "apps/brdfrig/target_commands.h"

#include <cstdio>
#include <memory>
#include <string>

#include "apps/brdfrig/board_options.h"
#include "calibrate/print_targets.h"
#include "common/error.h"
#include "common/yaml_reader.h"
#include "geometry/rig_geometry.h"
#include "rig/rig_file.h"

namespace brdfrig::apps {
namespace {

struct TargetArgs {
  std::string rig, scene, output;
  BoardArgs board;
  double mask_marker_mm = 0;
};

}  // namespace

void RegisterTargetCommands(CLI::App& app) {
  auto args = std::make_shared<TargetArgs>();
  CLI::App* target_cmd = app.add_subcommand("target", "Printable calibration targets");
  target_cmd->require_subcommand(1);
  CLI::App* print = target_cmd->add_subcommand(
      "print",
      "Write a ChArUco board and a marker mask (cut-out from the rig) as PDF and SVG at exact "
      "size, with targets.json");
  print->add_option("-o,--output", args->output, "Output directory")->required();
  auto* rig = print->add_option("--rig", args->rig, "rig.yaml: the mask's cut-out and paper");
  print->add_option("--scene", args->scene, "scene.yaml: the mask's cut-out and paper")
      ->excludes(rig);
  AddBoardOptions(print, args->board, false);
  print->add_option("--mask-marker-mm", args->mask_marker_mm,
                    "Side of the mask's markers in mm (default 20)");
  print->callback([args] {
    geometry::TargetGeometry target;
    if (!args->rig.empty()) {
      target = rig::ReadRigDescription(args->rig).geometry.target;
    } else if (!args->scene.empty()) {
      target = geometry::ParseRigGeometry(LoadYamlFile(args->scene).Required("rig")).target;
    } else {
      throw Error("target print: give --rig rig.yaml or --scene scene.yaml (the cut-out's size)");
    }
    calibrate::PrintTargetsOptions options;
    options.output_dir = args->output;
    options.board = BoardSpecFrom(args->board);
    options.mask = calibrate::MarkerMaskSpec::ForTarget(target);
    if (args->mask_marker_mm > 0) options.mask.marker_m = 1e-3 * args->mask_marker_mm;
    std::printf("%s\n", calibrate::PrintTargets(options).ToString().c_str());
  });
}

}  // namespace brdfrig::apps
