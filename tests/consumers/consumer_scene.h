// The one scene in which brdfrig's renderer and the glTF consumers (three.js, Blender's Cycles)
// draw an exported material, so their pictures can be compared pixel for pixel: a sphere of
// radius 1 at the origin, a pinhole camera on +z looking at it with +y up, and one directional
// light of irradiance 1 (W/m² on a surface facing it), nothing else: no environment, no
// indirect light, no tone mapping. Images are linear radiance, CV_32FC3 in OpenCV's B,G,R order,
// row 0 at the top.
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <string>

#include "brdf/brdf.h"
#include "evaluate/image_metrics.h"

namespace brdfrig::testing {

struct ConsumerView {
  int width = 96, height = 96;
  double distance = 10;                    // camera on +z, metres
  double fov_deg = 12.5;                   // vertical; the sphere fills about 90 % of the height
  Eigen::Vector3d light{0.45, 0.35, 1.0};  // towards the light (normalized where used)

  // The view as three_render.mjs's query parameters.
  std::string Query() const;
};

// brdfrig's own renderer (render::Renderer, the material's GLSL): the sphere under a point light
// 10 km away in the light's direction whose intensity gives irradiance 1 at the origin (the
// fall-off across the sphere is 2e-4, far below what the comparisons resolve).
cv::Mat RenderWithBrdfrig(const brdf::Brdf& material, const ConsumerView& view);

// The pixels whose centre ray meets the sphere where the surface faces the camera by at least
// `min_cos` (cos of the view angle): the silhouette, where a tessellated sphere and brdfrig's
// differ by their facets, is left out. CV_8UC1, 255 inside.
cv::Mat SphereInterior(const ConsumerView& view, double min_cos = 0.15);

// PSNR of `other` against `reference` over `mask` in linear radiance, all channels, the peak
// being the reference's 99th percentile over the mask (not its maximum: one highlight pixel
// would set the scale).
evaluate::PsnrResult CompareLinear(const cv::Mat& reference, const cv::Mat& other,
                                   const cv::Mat& mask);

// One of three_render.mjs's pictures ("spec" or "shipped": RGBA floats, rows bottom-up) as
// CV_32FC3 B,G,R with row 0 at the top.
cv::Mat ThreeJsImage(const nlohmann::json& result, const std::string& terms);

// blender_check.py's arguments after the file names: the view and the light, then `samples`.
std::string BlenderViewArguments(const ConsumerView& view, int samples);

// Where the consumers live: tests/consumers in the source tree, with node_modules installed by
// scripts/setup.sh. Empty when a tool is missing; `why` then says which.
std::filesystem::path ConsumersDir();
bool HaveProgram(const std::string& name);

}  // namespace brdfrig::testing
