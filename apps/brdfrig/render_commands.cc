#include "apps/brdfrig/render_commands.h"

#include <cstdio>
#include <filesystem>
#include <memory>

#include "brdf/brdf_file.h"
#include "jobs/render_job.h"
#include "reconstruct/gltf_export.h"
#include "render/viewer.h"

namespace brdfrig::apps {

void RegisterRenderCommands(CLI::App& app) {
  auto render_options = std::make_shared<jobs::RenderJobOptions>();
  CLI::App* render = app.add_subcommand(
      "render", "Render a material headless (a capture position of a scene, or a mesh)");
  render->add_option("material", render_options->material, "material.json or MERL .binary")
      ->required();
  render->add_option("--scene", render_options->scene, "render a capture position of this scene");
  render->add_option("--position", render_options->position, "capture position index (scene)");
  render->add_option("--mesh", render_options->mesh, "sphere | object | plane | file.obj");
  render->add_option("--width", render_options->width);
  render->add_option("--height", render_options->height);
  render->add_option("-o,--output", render_options->output, ".exr radiance or .png picture")
      ->required();
  render->callback([render_options] {
    const jobs::RenderJobSummary s = jobs::RunRenderJob(*render_options);
    std::printf("rendered %s -> %s\n", s.ToString().c_str(), render_options->output.c_str());
  });

  struct ExportArgs {
    std::string material, output;
  };
  auto export_args = std::make_shared<ExportArgs>();
  CLI::App* export_command = app.add_subcommand(
      "export",
      "Write a material (any model kind) as a MERL .binary table or a glTF 2.0 .glb / .gltf "
      "(docs/gltf.md), chosen by the output's extension");
  export_command->add_option("material", export_args->material, "material.json or MERL .binary")
      ->required();
  export_command
      ->add_option("-o,--output", export_args->output,
                   "MERL table (.binary), binary glTF (.glb) or glTF JSON (.gltf, with a .bin)")
      ->required();
  export_command->callback([export_args] {
    const std::filesystem::path output = export_args->output;
    if (output.extension() == ".glb" || output.extension() == ".gltf") {
      const reconstruct::GltfExportSummary s =
          reconstruct::ExportGltfFile(export_args->material, output);
      std::printf("exported %s -> %s (%s)\n", export_args->material.c_str(),
                  export_args->output.c_str(), s.ToString().c_str());
      return;
    }
    brdf::ExportMerlFile(export_args->material, export_args->output);
    std::printf("exported %s -> %s\n", export_args->material.c_str(), export_args->output.c_str());
  });

  struct ViewArgs {
    std::string material, compare;
    render::ViewerOptions viewer;
  };
  auto view_args = std::make_shared<ViewArgs>();
  CLI::App* view = app.add_subcommand("view", "Interactive viewer (needs a display)");
  view->add_option("material", view_args->material, "material.json or MERL .binary")->required();
  view->add_option("--compare", view_args->compare, "a second material shown side by side");
  view->add_option("--width", view_args->viewer.width);
  view->add_option("--height", view_args->viewer.height);
  view->add_option("--frames", view_args->viewer.frames,
                   "render N frames, save a screenshot and exit");
  view->add_option("--screenshot", view_args->viewer.screenshot_path);
  view->callback([view_args] {
    const auto material = brdf::LoadBrdfFile(view_args->material);
    std::shared_ptr<const brdf::Brdf> compare;
    if (!view_args->compare.empty()) compare = brdf::LoadBrdfFile(view_args->compare);
    render::RunViewer(*material, compare.get(), view_args->material, view_args->compare,
                      view_args->viewer);
  });
}

}  // namespace brdfrig::apps
