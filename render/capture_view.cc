#include "render/capture_view.h"

#include <algorithm>
#include <opencv2/imgproc.hpp>

namespace brdfrig::render {

std::unique_ptr<GpuMaterial> MakeGpuMaterial(const brdf::Brdf& brdf) {
  return GpuMaterial::ForBrdf(brdf);
}

cv::Mat RenderCaptureView(const CaptureView& capture, const brdf::Brdf& sample) {
  const geometry::TargetGeometry& t = capture.target;
  const auto cw = static_cast<float>(t.cutout_width), ch = static_cast<float>(t.cutout_height);
  const auto pw = static_cast<float>(t.paper_width), ph = static_cast<float>(t.paper_height);
  constexpr float kTable = 10.0f;  // far beyond any view of the rig
  const GpuMesh sample_mesh(MakeRectangle(-cw / 2, cw / 2, -ch / 2, ch / 2));
  const GpuMesh paper_mesh(MakeFrame(cw, ch, pw, ph));
  const GpuMesh table_mesh(MakeFrame(pw, ph, kTable, kTable));
  const std::unique_ptr<GpuMaterial> sample_material = MakeGpuMaterial(sample);
  if (capture.linear_interpolation) sample_material->SetLinearInterpolation(true);
  const std::unique_ptr<GpuMaterial> paper =
      GpuMaterial::Lambert(brdf::Rgb::Constant(t.paper_albedo));
  const std::unique_ptr<GpuMaterial> table = GpuMaterial::Lambert(capture.background_albedo);

  // Supersampling renders a finer image whose pixel centres fall on the same sub-pixel grid as
  // the simulator's: pixel u covers fine pixels u·n … u·n + n − 1.
  const int n = std::max(1, capture.supersampling);
  View fine = capture.view;
  geometry::Intrinsics& k = fine.intrinsics;
  k.width *= n;
  k.height *= n;
  k.fx *= n;
  k.fy *= n;
  k.cx = (k.cx + 0.5) * n - 0.5;
  k.cy = (k.cy + 0.5) * n - 0.5;
  Renderer renderer(k.width, k.height);
  renderer.Draw(fine, {capture.light},
                {{&sample_mesh, sample_material.get()},
                 {&paper_mesh, paper.get()},
                 {&table_mesh, table.get()}});
  const cv::Mat radiance = renderer.ReadRadiance();
  if (n == 1) return radiance;
  cv::Mat box;
  cv::resize(radiance, box, {capture.view.intrinsics.width, capture.view.intrinsics.height}, 0, 0,
             cv::INTER_AREA);
  return box;
}

}  // namespace brdfrig::render
