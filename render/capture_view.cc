#include "render/capture_view.h"

#include "brdf/analytic.h"
#include "brdf/merl.h"
#include "brdf/slice_model.h"

namespace brdfrig::render {

std::unique_ptr<GpuMaterial> MakeGpuMaterial(const brdf::Brdf& brdf) {
  if (const auto* slices = dynamic_cast<const brdf::SliceModel*>(&brdf)) {
    return GpuMaterial::SliceModel(*slices);
  }
  if (const auto* lambert = dynamic_cast<const brdf::Lambert*>(&brdf)) {
    return GpuMaterial::Lambert(lambert->albedo());
  }
  if (const auto* ggx = dynamic_cast<const brdf::Ggx*>(&brdf)) {
    return GpuMaterial::Ggx(ggx->params());
  }
  if (const auto* table = dynamic_cast<const brdf::MerlTable*>(&brdf)) {
    return GpuMaterial::Merl(*table);
  }
  return GpuMaterial::Merl(brdf::MerlTable::Tabulate(brdf));
}

cv::Mat RenderCaptureView(const CaptureView& capture, const brdf::Brdf& sample) {
  const rig::TargetGeometry& t = capture.target;
  const auto cw = static_cast<float>(t.cutout_width), ch = static_cast<float>(t.cutout_height);
  const auto pw = static_cast<float>(t.paper_width), ph = static_cast<float>(t.paper_height);
  constexpr float kTable = 10.0f;  // far beyond any view of the rig
  const GpuMesh sample_mesh(MakeRectangle(-cw / 2, cw / 2, -ch / 2, ch / 2));
  const GpuMesh paper_mesh(MakeFrame(cw, ch, pw, ph));
  const GpuMesh table_mesh(MakeFrame(pw, ph, kTable, kTable));
  const std::unique_ptr<GpuMaterial> sample_material = MakeGpuMaterial(sample);
  const std::unique_ptr<GpuMaterial> paper =
      GpuMaterial::Lambert(brdf::Rgb::Constant(t.paper_albedo));
  const std::unique_ptr<GpuMaterial> table = GpuMaterial::Lambert(capture.background_albedo);

  Renderer renderer(capture.view.intrinsics.width, capture.view.intrinsics.height);
  renderer.Draw(capture.view, {capture.light},
                {{&sample_mesh, sample_material.get()},
                 {&paper_mesh, paper.get()},
                 {&table_mesh, table.get()}});
  return renderer.ReadRadiance();
}

}  // namespace brdfrig::render
