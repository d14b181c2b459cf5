#include "tests/consumers/consumer_scene.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <vector>

#include "geometry/camera.h"
#include "render/gl_context.h"
#include "render/gpu_material.h"
#include "render/mesh.h"
#include "render/renderer.h"

namespace brdfrig::testing {
namespace {

constexpr double kLightDistance = 1e4;  // metres: a directional light within 2e-4

geometry::Intrinsics IntrinsicsOf(const ConsumerView& view) {
  // OpenCV pixel centres at integer coordinates: the image's centre is (w − 1)/2.
  const double f = 0.5 * view.height / std::tan(0.5 * view.fov_deg * M_PI / 180);
  return {view.width, view.height, f, f, 0.5 * (view.width - 1), 0.5 * (view.height - 1)};
}

}  // namespace

std::string ConsumerView::Query() const {
  const Eigen::Vector3d l = light.normalized();
  std::ostringstream q;
  q.precision(17);
  q << "width=" << width << "&height=" << height << "&distance=" << distance << "&fov=" << fov_deg
    << "&light=" << l.x() << "," << l.y() << "," << l.z() << "&irradiance=1";
  return q.str();
}

cv::Mat RenderWithBrdfrig(const brdf::Brdf& material, const ConsumerView& view) {
  const auto context = render::CreateHeadlessContext();
  const render::GpuMesh sphere(render::MakeSphere(1.0f, 256, 512));
  const auto gpu_material = render::GpuMaterial::ForBrdf(material);
  render::View camera;
  camera.intrinsics = IntrinsicsOf(view);
  camera.pose =
      geometry::LookAt({0, 0, view.distance}, geometry::Vec3::Zero(), geometry::Vec3::UnitY());
  camera.near = 1;
  camera.far = 100;
  const Eigen::Vector3d l = view.light.normalized();
  render::Renderer renderer(view.width, view.height);
  renderer.Draw(camera,
                {{l * kLightDistance, brdf::Rgb::Constant(kLightDistance * kLightDistance)}},
                {{&sphere, gpu_material.get()}});
  return renderer.ReadRadiance();
}

cv::Mat SphereInterior(const ConsumerView& view, double min_cos) {
  const geometry::Intrinsics k = IntrinsicsOf(view);
  const Eigen::Vector3d origin(0, 0, view.distance);
  cv::Mat mask(view.height, view.width, CV_8UC1, cv::Scalar(0));
  for (int row = 0; row < view.height; ++row) {
    for (int col = 0; col < view.width; ++col) {
      // Camera looking down −z with +y up: image x is world x, image y (down) is world −y.
      const Eigen::Vector3d d =
          Eigen::Vector3d((col - k.cx) / k.fx, -(row - k.cy) / k.fy, -1).normalized();
      const double b = origin.dot(d);
      const double disc = b * b - (origin.squaredNorm() - 1);
      if (disc <= 0) continue;
      const Eigen::Vector3d hit = origin + (-b - std::sqrt(disc)) * d;
      if (hit.normalized().dot(-d) >= min_cos) mask.at<uint8_t>(row, col) = 255;
    }
  }
  return mask;
}

evaluate::PsnrResult CompareLinear(const cv::Mat& reference, const cv::Mat& other,
                                   const cv::Mat& mask) {
  std::vector<float> values;
  for (int row = 0; row < reference.rows; ++row) {
    for (int col = 0; col < reference.cols; ++col) {
      if (mask.at<uint8_t>(row, col) == 0) continue;
      const cv::Vec3f& v = reference.at<cv::Vec3f>(row, col);
      values.insert(values.end(), {v[0], v[1], v[2]});
    }
  }
  if (values.empty()) return evaluate::Psnr(reference, other, mask, 1, "empty");
  const size_t k = static_cast<size_t>(0.99 * (values.size() - 1));
  std::nth_element(values.begin(), values.begin() + k, values.end());
  return evaluate::Psnr(reference, other, mask, values[k],
                        "sphere interior (view cosine >= 0.15), linear radiance, peak = the "
                        "reference's 99th percentile");
}

cv::Mat ThreeJsImage(const nlohmann::json& result, const std::string& terms) {
  const int width = result.at("width"), height = result.at("height");
  const std::vector<float> rgba = result.at("rgba").at(terms).get<std::vector<float>>();
  cv::Mat image(height, width, CV_32FC3);
  for (int row = 0; row < height; ++row) {
    for (int col = 0; col < width; ++col) {
      const float* p = &rgba[4 * ((height - 1 - row) * width + col)];
      image.at<cv::Vec3f>(row, col) = {p[2], p[1], p[0]};
    }
  }
  return image;
}

std::string BlenderViewArguments(const ConsumerView& view, int samples) {
  const Eigen::Vector3d l = view.light.normalized();
  char arguments[512];
  std::snprintf(arguments, sizeof arguments, "%d %d %.17g %.17g %.17g %.17g %.17g %d", view.width,
                view.height, view.distance, view.fov_deg, l.x(), l.y(), l.z(), samples);
  return arguments;
}

std::filesystem::path ConsumersDir() {
  return std::filesystem::path(BRDFRIG_SOURCE_DIR) / "tests" / "consumers";
}

bool HaveProgram(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path == nullptr ? "" : path);
  for (std::string dir; std::getline(dirs, dir, ':');) {
    if (!dir.empty() && ::access((std::filesystem::path(dir) / name).c_str(), X_OK) == 0) {
      return true;
    }
  }
  return false;
}

}  // namespace brdfrig::testing
