#include "jobs/render_job.h"

#include <Eigen/Geometry>
#include <chrono>
#include <cmath>
#include <sstream>

#include "brdf/brdf_file.h"
#include "common/error.h"
#include "common/option_check.h"
#include "evaluate/display_image.h"
#include "geometry/camera.h"
#include "render/capture_view.h"
#include "render/gl_context.h"
#include "sim/scene.h"
#include "sim/simulator.h"

namespace brdfrig::jobs {
namespace {

render::Mesh MeshByName(const std::string& name) {
  if (name == "sphere") return render::MakeSphere(0.06f, 128, 256);
  if (name == "object") return render::MakeTestObject(50000);
  if (name == "plane") return render::MakeRectangle(-0.1f, 0.1f, -0.1f, 0.1f);
  return render::LoadObj(name);
}

render::View OrbitView(int width, int height) {
  render::View view;
  view.intrinsics = {width, height, 1.2 * height, 1.2 * height, width / 2.0, height / 2.0};
  view.pose = geometry::LookAt({0.15, -0.25, 0.2}, geometry::Vec3::Zero(), geometry::Vec3::UnitZ());
  return view;
}

// A material the CPU evaluates finitely can overflow float on the GPU (A1 = 4e38): such an
// image, and a black one of a material that is not black, is an error, never a picture.
void CheckRendered(const cv::Mat& radiance, const brdf::Brdf& material,
                   const RenderJobOptions& options) {
  const cv::Mat values = radiance.reshape(1);
  int non_finite = 0;
  for (int r = 0; r < values.rows; ++r) {
    const float* row = values.ptr<float>(r);
    for (int c = 0; c < values.cols; ++c) non_finite += !std::isfinite(row[c]);
  }
  const std::string nothing = "; nothing written to " + options.output.string();
  if (non_finite > 0) {
    throw FileError(options.material.string(),
                    "the renderer computed " + std::to_string(non_finite) +
                        " infinite or NaN values (the material's values exceed float range)" +
                        nothing);
  }
  const brdf::Vec3 n = brdf::Vec3::UnitZ();
  if (cv::countNonZero(values) == 0 && (material.Eval(n, n, n) > 0).any()) {
    throw FileError(options.material.string(),
                    "the rendered image is black although the material is not" + nothing);
  }
}

}  // namespace

void RenderJobOptions::Validate() const {
  if (material.empty()) throw OptionsError("render: a material file is required");
  if (output.empty()) throw OptionsError("render: -o OUTPUT is required");
  CheckOption(width >= 1, "RenderJobOptions.width", width, ">= 1");
  CheckOption(height >= 1, "RenderJobOptions.height", height, ">= 1");
  CheckOption(position >= 0, "RenderJobOptions.position", position, ">= 0");
}

std::string RenderJobSummary::ToString() const {
  std::ostringstream out;
  out << width << "x" << height << " in " << milliseconds << " ms on " << gl;
  return out.str();
}

RenderJobSummary RunRenderJob(const RenderJobOptions& options) {
  options.Validate();
  const std::shared_ptr<const brdf::Brdf> material = brdf::LoadBrdfFile(options.material);
  const auto context = render::CreateHeadlessContext();
  RenderJobSummary summary;
  summary.gl = context->Description();
  const auto start = std::chrono::steady_clock::now();
  cv::Mat radiance;
  if (!options.scene.empty()) {
    const sim::Scene scene = sim::LoadScene(options.scene);
    if (options.position >= static_cast<int>(scene.capture.positions.size())) {
      throw OptionsError("render: --position " + std::to_string(options.position) + " but " +
                         options.scene.string() + " has " +
                         std::to_string(scene.capture.positions.size()) + " capture positions");
    }
    const sim::TrueGeometry g =
        sim::Simulator(scene.Ideal()).GeometryAt(scene.capture.positions[options.position]);
    render::CaptureView capture;
    capture.target = scene.rig.target;
    capture.background_albedo = scene.background_albedo;
    capture.view = {g.intrinsics, g.camera};
    capture.light = {g.light_position, brdf::Rgb::Constant(g.light_intensity)};
    radiance = render::RenderCaptureView(capture, *material);
  } else {
    const render::GpuMesh mesh(MeshByName(options.mesh));
    const auto gpu_material = render::MakeGpuMaterial(*material);
    render::Renderer renderer(options.width, options.height);
    renderer.Draw(OrbitView(options.width, options.height),
                  {{{0.2, -0.1, 0.3}, brdf::Rgb::Constant(0.02)}}, {{&mesh, gpu_material.get()}});
    radiance = renderer.ReadRadiance();
  }
  summary.milliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  summary.width = radiance.cols;
  summary.height = radiance.rows;
  CheckRendered(radiance, *material, options);
  evaluate::WriteImageFile(options.output, radiance);
  return summary;
}

}  // namespace brdfrig::jobs
